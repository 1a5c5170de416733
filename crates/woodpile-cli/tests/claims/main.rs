//! Claims of the `woodpile` command line, each run through the real binary.
//!
//! One test binary per crate (link time dominates the suite): each module below is one claim,
//! and opens with the claim it checks and the reason for its tolerance.

mod actuator_rest_output;
mod atomic_output;
mod bad_input_exit_2;
mod blast_table;
mod blowup_exit_1;
mod builtins_run;
mod cells_from_rod;
mod cells_table;
mod checkpoint_integrity;
mod common;
mod default_job;
mod fit_bad_input;
mod fit_command;
mod fit_interrupt;
mod interrupt_within_a_run;
mod lattice_builtin;
mod lattice_chains_only;
mod lattice_displacement_run;
mod lattice_lab_run;
mod lattice_rod_keys;
mod lattice_run;
mod meaningless_inputs_refused;
mod meaningless_results;
mod meaningless_study_inputs;
mod one_run_layout;
mod optimize_bad_input;
mod optimize_best_reruns;
#[cfg(unix)]
mod optimize_interrupt_resume;
mod optimize_lattice;
mod optimize_layers;
mod optimize_pareto;
mod optimize_robust;
mod optimize_robust_nsga2;
mod output_files;
mod paper_values_stated_once;
mod plot_opt_dir;
mod plot_run_dir;
mod progress_lines;
mod readme_file_table;
mod report_quick;
mod scenario_roundtrip;
mod sensitivity_command;
mod simulate_samples;
mod stdout_failures;
mod study_directories;
mod study_size_limits;
mod transmission_command;
mod up_front_limits;

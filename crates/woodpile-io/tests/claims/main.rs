//! Claims of the file formats shared by every front end.
//!
//! One test binary per crate (link time dominates the suite): each module below is one claim,
//! and opens with the claim it checks and the reason for its tolerance.

mod checkpoint_layers_resume;
mod checkpoint_screened_resume;
mod element_angles_and_mass_in_mass;
mod errors_speak_no_front_end;
mod fit_modulus_scale;
mod fuzz_corpus;
mod lab_scenario_keys;
mod lattice_keys_table;
mod lattice_study;
mod pareto_checkpoint_resume;
mod peak_tolerance_key;
mod rod_range_catalogue;
mod run_directory_roundtrip;
mod scenario_keys_table;
mod study_defaults_same_choices;
mod study_refusals;
mod uncertainty_table;

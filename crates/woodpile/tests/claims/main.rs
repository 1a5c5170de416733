//! Claims of the physics and numerics core, each checked against a closed form, an independent computation or a stated invariant.
//!
//! One test binary per crate (link time dominates the suite): each module below is one claim,
//! and opens with the claim it checks and the reason for its tolerance.

mod analysis_band_gaps;
mod analysis_energy_map;
mod analysis_fft_vs_dft;
mod analysis_layer_protocol;
mod analysis_parseval;
mod analysis_pulses;
mod analysis_sine_spectrum;
mod analysis_spectrum_record_length;
mod beam_euler_bernoulli_limit;
mod beam_timoshenko_frequencies;
mod blast_energy_balance;
mod blowup_detection;
mod cell_from_rod;
mod cell_reduction_in_time;
mod cell_table1_frequencies;
mod cell_table1_from_beam;
mod collision;
mod contact_beta_reference;
mod convergence_order;
mod damped_effective_mass;
mod damping_hunt_crossley;
mod damping_restitution;
mod damping_zero_bit_identical;
mod energy_conservation_impact;
mod event_stepping_accuracy;
mod exact_modes;
mod fe_rod_frequencies;
mod lab_energy_balance;
mod lanes_bit_identical;
mod lanes_common;
mod lanes_figures_of_merit;
mod lanes_lab_physics;
mod nesterenko_solitary_wave;
mod no_tension;
mod optimize_cache_transparent;
mod optimize_common;
mod optimize_exhaustive_tiny;
mod optimize_operators_feasible;
mod optimize_resume;
mod optimize_screening;
mod optimize_stop_early;
mod optimize_thread_determinism;
mod peak_refinement;
mod peak_tolerance_bound;
mod preload_static_equilibrium;
mod rk4_dopri5_agreement;
mod run_limits;
mod simd_step_bit_identical;
mod table_load_peak;
mod transmission_band_edges;
mod two_body_hertz_impact;

//! Spectra, spatio-temporal maps, effective-mass curves, band gaps and the layer-by-layer
//! protocol. Placeholder: being written.

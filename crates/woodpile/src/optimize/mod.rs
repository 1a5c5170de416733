//! Breeder genetic algorithm for the element arrangement that transmits the least force
//! (model.md §11). Placeholder: being written.

//! Events: where they are located against exact event times, what each
//! action does to a run of every method, and the typed errors.

mod actions;
mod errors;
mod location;

//! The command line's parts: flag types and parsers, the shared flags,
//! input loading.

pub(crate) mod choices;
pub(crate) mod common;
pub(crate) mod layers;
pub(crate) mod load;
pub(crate) mod parse;
pub(crate) mod radiosity;
pub(crate) mod trace;
pub(crate) mod visibility;

//! The uniform grid (being written).

//! The kd-tree (being written).

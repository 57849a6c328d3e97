//! autosim-core

//! Typed indices (like cranelift's entities): a `u32` newtype per table,
//! so an expression id cannot index the body table.

/// Declares an index newtype with `index()`.
macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident, $what:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub struct $name(pub(crate) u32);

        impl $name {
            #[doc = concat!("Position in the ", $what, ".")]
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }
    };
}

pub(crate) use id_type;

//! Named parameter sets generic over the scalar type.
//!
//! Every model parameter has a name (`"A"`, `"E"`, ...) so that a fit can seed any subset
//! of them with dual parts and get dσ/d(parameter) from the same code (NEML2-style
//! parameter derivatives next to state derivatives).

/// Declares a parameter struct `Name<D = f64>` with one named field per parameter, plus
/// `NAMES`, `map` (convert or seed each value by name), `from_names`, `get` and `set`.
#[macro_export]
macro_rules! parameter_set {
    ($(#[$doc:meta])* $name:ident { $($(#[$fdoc:meta])* $field:ident => $key:literal),* $(,)? }) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name<D = f64> {
            $($(#[$fdoc])* pub $field: D,)*
        }

        impl<D: Copy> $name<D> {
            /// Parameter names, in field order.
            pub const NAMES: &'static [&'static str] = &[$($key),*];

            /// Apply `f(name, value)` to every parameter.
            pub fn map<E>(&self, mut f: impl FnMut(&'static str, D) -> E) -> $name<E> {
                $name { $($field: f($key, self.$field),)* }
            }

            /// The set with each parameter `value(name)`.
            pub fn from_names(value: impl Fn(&'static str) -> D) -> Self {
                $name { $($field: value($key),)* }
            }

            pub fn get(&self, key: &str) -> Option<D> {
                match key {
                    $($key => Some(self.$field),)*
                    _ => None,
                }
            }

            /// Set a parameter by name; returns false if the name is not one of `NAMES`.
            pub fn set(&mut self, key: &str, value: D) -> bool {
                match key {
                    $($key => { self.$field = value; true })*
                    _ => false,
                }
            }
        }
    };
}

//! Flecnodal curves: points with an asymptotic tangent line of 4-point contact. The exact
//! system in `(u, v, s)` ([`system`]) and its certified curves per patch ([`curves`]).

pub mod curves;
pub mod system;

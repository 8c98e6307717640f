//! Generators of random and degenerate inputs for property tests (proptest strategies and
//! quickcheck `Arbitrary` implementations), for limn's own tests and for users' fuzzing.

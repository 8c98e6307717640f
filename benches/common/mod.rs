//! Helpers shared by the benches: a view direction, a thread pool, and the IGES coil spring
//! for the runs behind `LIMN_BENCH_SPRING=1`.

use limn::analysis::view::View;
use limn::model::{Model, WeldTolerance};
use limn::number::Rational;

/// The parallel view along `d`.
pub fn view(d: [i64; 3]) -> View {
    View::Direction(d.map(Rational::from))
}

/// A pool of `threads` workers.
pub fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// The IGES coil spring (1,062 patches) with its default weld, if `LIMN_BENCH_SPRING` is set.
pub fn spring_if_asked() -> Option<(Model, WeldTolerance)> {
    std::env::var_os("LIMN_BENCH_SPRING")?;
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/iges/occt/bug22869_Spring.igs"
    );
    let spring = limn::io::read_model(std::path::Path::new(path)).unwrap();
    let weld = limn::model::default_weld(&spring);
    Some((spring, weld))
}

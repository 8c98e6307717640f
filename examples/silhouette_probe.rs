//! Prints a summary of the silhouette of a model file for a direction (development probe).
use limn::analysis::silhouette::{parse_vector, silhouette, View};
use limn::model::default_weld;
use limn::solver::CurveOptions;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let m = limn::io::read_model(std::path::Path::new(&args[1])).expect("model");
    let v = parse_vector(&args[2]).expect("direction");
    let t = std::time::Instant::now();
    let s = silhouette(
        &m,
        &View::Direction(v),
        &CurveOptions::default(),
        default_weld(&m),
    );
    let el = t.elapsed();
    println!("{} curves ({} closed, {} certified), {} unresolved boxes, {} unjoined edges, {} degenerate, {} boxes, escalated {} in {:?}",
        s.curves.len(), s.curves.iter().filter(|c| c.closed).count(), s.curves.iter().filter(|c| c.certified_topology).count(),
        s.unresolved.len(), s.unjoined_edges.len(), s.degenerate.len(), s.boxes, s.escalations.escalated(), el);
    for u in s.unresolved.iter().take(5) {
        println!("  unresolved patch {} {:?}: {}", u.0, u.1.to_f64(), u.2);
    }
    for e in s.unjoined_edges.iter().take(5) {
        println!("  unjoined {:?}", e);
    }
    for c in s.curves.iter().take(12) {
        println!(
            "  curve patches {:?} closed {} certified {} points {}",
            c.patches,
            c.closed,
            c.certified_topology,
            c.points.len()
        );
    }
}

use linkage::Mechanism;
use linkage_examples::stewart::*;
fn main() {
    let s = Stewart::new();
    println!("{}", Stewart::LISTING);
    for (n, c) in Stewart::CONSTANT_NAMES.iter().zip(s.constants()) { print!("{n}={c:.4} "); }
    println!();
    let st = home_start(&s).unwrap();
    println!("{:?}", st);
    println!("{:?}", linkage::pose_from_unknowns(&s, &st.v).map(|p| (p.euler(), p.translation)));
    let target = [190.0, 200.0, 190.0, 180.0, 190.0, 210.0];
    for m in [linkage::Method::ArcLength, linkage::Method::NewtonHomotopy, linkage::Method::NewtonRaphson] {
        let sol = m.solve(&s, &st, &target, &linkage::Options::TIGHT).unwrap();
        println!("{m:?} {:?} acc {} rej {} it {} err {:e} mindet {:.3}", sol.status, sol.steps_accepted, sol.steps_rejected, sol.newton_iterations, sol.error_estimate, sol.min_det_ratio);
        println!("   {:?}", s.inverse(&sol.v, &target));
    }
    let _ = Stewart::NNZ;
}

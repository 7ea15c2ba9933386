use linkage::{Mechanism, Pose, Method, Options, Status};
use linkage_examples::stewart::*;
fn rnd(s: &mut u64) -> f64 { *s ^= *s << 13; *s ^= *s >> 7; *s ^= *s << 17; (*s >> 11) as f64 / (1u64<<53) as f64 }
fn main() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let home = linkage::pose_from_unknowns(&s, &st.v).unwrap();
    let [hy, hp, hr] = home.euler();
    let ht = home.translation;
    let mut seed = 12345u64;
    let mut counts = std::collections::BTreeMap::new();
    for _ in 0..2000 {
        let u: Vec<f64> = (0..6).map(|i| if i < 3 { (rnd(&mut seed)*2.0-1.0)*1.2 } else { (rnd(&mut seed)*2.0-1.0)*150.0 }).collect();
        // nonsingular pose path check
        let mut ok = true; let mut last = None;
        for k in 0..=100 {
            let t = k as f64 / 100.0;
            let p = Pose::from_euler(hy + t*u[0], hp + t*u[1], hr + t*u[2], [ht[0]+t*u[3], ht[1]+t*u[4], ht[2]+t*u[5]]);
            let Some((x, v)) = legs_for_pose(&s, &p) else { ok = false; break };
            let d = linkage::det_b(&s, &v, &x);
            if d * st.det <= 0.0 || x.iter().any(|l| *l < 50.0) { ok = false; break; }
            last = Some((x, v, d));
        }
        if !ok { continue; }
        let (x, v, d) = last.unwrap();
        let near = (d / st.det).abs() < 0.05;
        for m in [Method::ArcLength, Method::NewtonHomotopy, Method::NewtonRaphson] {
            let sol = m.solve(&s, &st, &x, &Options::TIGHT).unwrap();
            let err = sol.v.iter().zip(&v).map(|(a,b)| (a-b).abs()).fold(0.0, f64::max);
            if m == Method::ArcLength && sol.status == Status::Converged && err > 1e-6 {
                // fine natural continuation along the straight segment
                let mut w = st.v; let mut mind = f64::INFINITY; let mut flips = 0; let mut prev = st.det;
                let n = 20000;
                for k in 1..=n { let l = k as f64 / n as f64; let xx: [f64;6] = std::array::from_fn(|j| st.x[j] + l*(x[j]-st.x[j]));
                    for _ in 0..4 { let mut f=[0.0;18]; s.residual(&w,&xx,&mut f); let mut b=[[0.0;18];18]; s.jacobian_dense(&w,&xx,&mut b); let piv = linkage::lu::factor::<18,_>(&mut b).unwrap(); linkage::lu::solve(&b,&piv,&mut f); for i in 0..18 { w[i]-=f[i]; } }
                    let d = linkage::det_b(&s,&w,&xx); if d*prev <= 0.0 { flips += 1; } prev = d; mind = mind.min((d/st.det).abs()); }
                let e2 = w.iter().zip(&sol.v).map(|(a,b)| (a-b).abs()).fold(0.0, f64::max);
                let e3 = w.iter().zip(&v).map(|(a,b)| (a-b).abs()).fold(0.0, f64::max);
                let mut pmin = f64::INFINITY; let mut pflips = 0;
                for k in 0..=20000 { let t = k as f64 / 20000.0;
                    let p = Pose::from_euler(hy + t*u[0], hp + t*u[1], hr + t*u[2], [ht[0]+t*u[3], ht[1]+t*u[4], ht[2]+t*u[5]]);
                    let (xx, vv) = legs_for_pose(&s, &p).unwrap(); let d = linkage::det_b(&s, &vv, &xx); if d*st.det <= 0.0 { pflips += 1; } pmin = pmin.min((d/st.det).abs()); }
                println!("pose path: flips {pflips} min ratio {pmin:.2e}");
                println!("WRONG: err {err:.3} fine-vs-PH {e2:.2e} fine-vs-truth {e3:.3} flips {flips} min det ratio {mind:.2e} PH min {:.2e} acc {} rej {}", sol.min_det_ratio, sol.steps_accepted, sol.steps_rejected);
            }
            let key = format!("{m:?} near={near} {} {}", sol.status.word(), if sol.status == Status::Converged { if err < 1e-6 {"right"} else {"WRONG"} } else {""});
            *counts.entry(key).or_insert(0) += 1;
        }
    }
    for (k, v) in counts { println!("{k}: {v}"); }
    let _ = Stewart::NNZ;
}

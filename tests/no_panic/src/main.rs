//! Links every `#[no_panic]` entry point of the library (the proof), then runs them once on
//! good and on bad input (a smoke test that they are the real thing).

use core::hint::black_box;
use linkage::{Mechanism, Options, Pose, Tracker};
use no_panic_proof::{hexapod, rps, stewart, Rps, RssHexapod, Stewart};

fn main() {
    let o = black_box(Options::TIGHT);

    let sys = Rps::new();
    let v0 = linkage::unknowns_from_pose(&sys, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    let x0 = sys.inverse(&v0, &[0.0; 3]).expect("the 3-RPS at home");
    let s = rps::start(&sys, v0, x0).expect("the 3-RPS's start");
    let x = black_box([160.0, 155.0, 158.0]);
    let sol = rps::ph(&sys, &s, &x, &o).expect("a solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    assert!(rps::nr(&sys, &s, &x, &o).is_ok() && rps::nh(&sys, &s, &x, &o).is_ok());
    assert!(rps::detour(&sys, &s, &x, &o).is_ok());
    assert!(rps::proof(&sys, &sol.v, &x).is_ok());
    let mut t = Tracker::new(sys.clone(), s, o);
    assert!(rps::track(&mut t, &x).is_ok());
    let bad = black_box([f64::NAN, 155.0, 158.0]);
    assert!(rps::nr(&sys, &s, &bad, &o).is_err() && rps::ph(&sys, &s, &bad, &o).is_err());
    assert!(rps::track(&mut t, &bad).is_err() && rps::proof(&sys, &sol.v, &bad).is_err());
    assert!(rps::start(&sys, [f64::NAN; 9], x0).is_err());

    let sys = Stewart::new();
    let v0 = linkage::unknowns_from_pose(
        &sys,
        &Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 159.011]),
    );
    let x0 = sys
        .inverse(&v0, &[170.0; 6])
        .expect("the Stewart platform at home");
    let s = stewart::start(&sys, v0, x0).expect("the Stewart platform's start");
    let x = black_box([175.0, 172.0, 168.0, 171.0, 169.0, 173.0]);
    let sol = stewart::ph(&sys, &s, &x, &o).expect("a solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    assert!(stewart::nr(&sys, &s, &x, &o).is_ok() && stewart::nh(&sys, &s, &x, &o).is_ok());
    assert!(stewart::detour(&sys, &s, &x, &o).is_ok());
    assert!(stewart::proof(&sys, &sol.v, &x).is_ok());
    let mut t = Tracker::new(sys.clone(), s, o);
    assert!(stewart::track(&mut t, &x).is_ok());
    let bad = black_box([f64::INFINITY; 6]);
    assert!(stewart::nr(&sys, &s, &bad, &o).is_err() && stewart::track(&mut t, &bad).is_err());
    let sys = RssHexapod::new();
    let s = sys.home_start().expect("the hexapod's start");
    let x = black_box(s.x().map(|q| q + 0.05));
    let sol = hexapod::ph(&sys, &s, &x, &o).expect("a solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    assert!(hexapod::nr(&sys, &s, &x, &o).is_ok() && hexapod::proof(&sys, &sol.v, &x).is_ok());
    let mut t = Tracker::new(sys.clone(), s, o);
    assert!(hexapod::track(&mut t, &x).is_ok());
    assert!(hexapod::nh(&sys, &s, &black_box([f64::NAN; 6]), &o).is_err());
    println!("no-panic proof: linked; every entry point ran on good and bad input");
}

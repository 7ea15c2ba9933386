//! The `stewart` command line's pieces: file formats, start configurations, any 6-6 geometry.

use linkage::{arc_length, pose_from_unknowns, Mechanism, Options, Pose, Status};
use linkage_examples::cli::{geometry, legs_csv};
use linkage_examples::stewart::{
    find_start, home_start, legs_for_pose, platform_is_coplanar, SixSix, StartError, Stewart,
    StewartGeneral, HOME_LEGS,
};
use linkage_tests::{max_diff, Rng};

#[test]
fn the_default_start_is_the_papers_home() {
    let s = Stewart::new();
    let found = find_start(&s, HOME_LEGS, None).unwrap();
    let home = home_start(&s).unwrap();
    assert!(max_diff(found.v(), home.v()) < 1e-9);
}

#[test]
fn malformed_geometry_files_give_clear_messages() {
    let ok = "base = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\nplatform = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\n[start]\nlegs = [1,1,1,1,1,1]\n";
    assert!(geometry::parse(ok).is_ok());
    let cases = [
        (
            "base = [[0,0,0]]\nplatform = []\n[start]\nlegs = []",
            "`base` needs 6 entries",
        ),
        (
            &ok.replace("legs = [1,1,1,1,1,1]", "legs = [1,1,1,1,1,-1]"),
            "start leg L6 must be positive",
        ),
        (
            &ok.replace("legs = [1,1,1,1,1,1]", "legs = [1,1,1,1,1,nan]"),
            "finite",
        ),
        (
            &ok.replace("[start]", "[start]\ncolour = 3"),
            "unknown field",
        ),
        ("base = ", "parse error at line 1"),
        (
            &ok.replace(
                "legs = [1,1,1,1,1,1]",
                "legs = [1,1,1,1,1,1]\npose = [0, 0]",
            ),
            "`start.pose` needs 6 entries",
        ),
    ];
    for (text, want) in cases {
        let err = geometry::parse(text).err().unwrap_or_default();
        assert!(
            err.to_lowercase().contains(&want.to_lowercase()),
            "{text:?}: {err}"
        );
    }
}

#[test]
fn leg_csv_rows_carry_their_own_status() {
    let dir = std::env::temp_dir().join(format!("linkage-csv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("legs.csv");
    std::fs::write(
        &path,
        "t,L6,L5,L4,L3,L2,L1\n0,6,5,4,3,2,1\n1,1,2\n2,x,1,1,1,1,1\n3,inf,1,1,1,1,1\n",
    )
    .unwrap();
    let rows = legs_csv::read(&path).unwrap();
    assert_eq!(
        rows[0],
        Ok([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
        "columns found by name"
    );
    assert_eq!(rows[1], Err("missing_value"));
    assert_eq!(rows[2], Err("invalid_number"));
    assert_eq!(rows[3], Err("non_finite"));
    std::fs::write(&path, "a,b\n1,2\n").unwrap();
    assert!(legs_csv::read(&path)
        .unwrap_err()
        .contains("no column `L1`"));
    // A repeated column is ambiguous: an error, not the first one silently.
    let twice = legs_csv::read_from(&b"L1,L2,L3,L4,L5,L6,L2\n1,2,3,4,5,6,7\n"[..]);
    assert!(twice.unwrap_err().contains("`L2` twice (columns 2 and 7)"));
    // Bytes that are not UTF-8: harmless in an ignored column, the row's own status in a leg.
    let bytes = b"x,L1,L2,L3,L4,L5,L6\n\xff,1,2,3,4,5,6\n0,1,\xff,3,4,5,6\n0,1,2,3,4,5,6\n";
    assert_eq!(
        legs_csv::read_from(&bytes[..]).unwrap(),
        [
            Ok([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
            Err("invalid_number"),
            Ok([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
        ]
    );
    assert!(legs_csv::read(&dir.join("missing.csv")).is_err());
}

/// A row with a field more or fewer than the header was read by position: `0,170,1,170,…`
/// with one value too many under `t,L1…L6` gave L2 = 1 and was solved, its answer `ok` for leg
/// lengths no one wrote; a row one field short but with every `L` column present was solved
/// too. Either is now the row's own status, and an empty field past the header's (a trailing
/// comma) is still harmless.
#[test]
fn a_row_with_a_field_more_or_fewer_than_the_header_is_refused() {
    let text = b"t,L1,L2,L3,L4,L5,L6,note\n\
        0,170,170,170,170,170,170,a\n\
        1,170,1,170,170,170,170,170,a\n\
        2,170,170,170,170,170,170\n\
        3,170,170,170,170,170,170,a,\n\
        4,170,170,170,170,170,170,a, ,\n";
    assert_eq!(
        legs_csv::read_from(&text[..]).unwrap(),
        [
            Ok([170.0; 6]),
            Err("extra_value"),
            Err("missing_value"),
            Ok([170.0; 6]),
            Ok([170.0; 6]),
        ]
    );
}

/// Files as other programs write them: a UTF-8 byte-order mark before the header (a
/// spreadsheet's "CSV UTF-8"), CRLF or bare CR line ends, a blank line between rows, quoted
/// fields. Each row is read, none is lost, and the header is found; a geometry file with a key
/// or section given twice is an error naming it, not the first or last one silently.
#[test]
fn leg_files_from_other_programs_read_every_row() {
    let want = [
        Ok([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
        Ok([6.0, 5.0, 4.0, 3.0, 2.0, 1.0]),
    ];
    for text in [
        &b"\xef\xbb\xbfL1,L2,L3,L4,L5,L6\n1,2,3,4,5,6\n6,5,4,3,2,1\n"[..],
        b"L1,L2,L3,L4,L5,L6\r\n1,2,3,4,5,6\r\n6,5,4,3,2,1\r\n",
        b"L1,L2,L3,L4,L5,L6\r1,2,3,4,5,6\r6,5,4,3,2,1",
        b"\"L1\",\"L2\",L3,L4,L5,L6\n\n\"1\",2, 3 ,4,5,6\n\n6,5,4,3,2,1\n",
    ] {
        let rows = legs_csv::read_from(text);
        assert_eq!(
            rows.as_deref(),
            Ok(&want[..]),
            "{:?}",
            String::from_utf8_lossy(text)
        );
    }
    let ok = "base = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\nplatform = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\n[start]\nlegs = [1,1,1,1,1,1]\n";
    for twice in [
        format!("{ok}legs = [2,2,2,2,2,2]\n"),
        format!("platform = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\n{ok}"),
        format!("{ok}[start]\nlegs = [2,2,2,2,2,2]\n"),
    ] {
        let err = geometry::parse(&twice).err().unwrap_or_default();
        assert!(err.contains("duplicate key"), "{twice:?}: {err}");
    }
}

/// A quote left open takes every line after it into one field, which the CSV parser accepts
/// at the end of the input: the rows it swallowed were lost without a word (one
/// `missing_value` row stood for all of them). It is a read error naming the quote's line,
/// after the rows before it; quoted fields that close, `""` inside one, a quote inside an
/// unquoted field and a line break inside a closed quoted field stay readable.
#[test]
fn a_quote_left_open_is_an_error_not_lost_rows() {
    for text in [
        &b"L1,L2,L3,L4,L5,L6\n1,2,3,4,5,6\n\"6,5,4,3,2,1\n1,1,1,1,1,1\n"[..],
        b"L1,L2,L3,L4,L5,L6\r\n1,2,3,4,5,6\r\n\"6,5,4,3,2,1\r\n1,1,1,1,1,1",
        b"L1,L2,L3,L4,L5,L6,note\n1,2,3,4,5,6,x\n6,5,4,3,2,1,\"a \"\"b\"\"\n",
    ] {
        let mut rows = legs_csv::LegRows::new(text).unwrap();
        assert_eq!(
            rows.next_row(),
            Ok(Some(Ok([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])))
        );
        let err = rows.next_row().unwrap_err();
        assert!(
            err.contains("quoted field") && err.contains("line 3"),
            "{err}"
        );
    }
    let fine = b"L1,L2,L3,L4,L5,L6,note\n1,2,3,4,5,6,\"a \"\"b\"\" c\"\n6,5,4,3,2,1,x\"y\n1,1,1,1,1,1,\"two\nlines\"\n";
    let rows = legs_csv::read_from(&fine[..]).unwrap();
    assert_eq!(
        rows,
        [
            Ok([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
            Ok([6.0, 5.0, 4.0, 3.0, 2.0, 1.0]),
            Ok([1.0; 6])
        ]
    );
}

/// A random 6-6 geometry around Table III's, optionally lifting pivots off their planes.
fn random_geometry(
    rng: &mut Rng,
    lift_platform: bool,
    lift_base: bool,
) -> ([[f64; 3]; 6], [[f64; 3]; 6]) {
    let s = Stewart::new();
    let g = s.geometry();
    let mut base = [[0.0; 3]; 6];
    let mut platform = [[0.0; 3]; 6];
    for i in 0..6 {
        for a in 0..3 {
            base[i][a] = g[3 * i + a]
                + if a < 2 {
                    rng.uniform(-10.0, 10.0)
                } else if lift_base {
                    rng.uniform(-15.0, 15.0)
                } else {
                    0.0
                };
            platform[i][a] = g[18 + 3 * i + a]
                + if a < 2 {
                    rng.uniform(-10.0, 10.0)
                } else if lift_platform {
                    rng.uniform(-15.0, 15.0)
                } else {
                    0.0
                };
        }
    }
    (base, platform)
}

fn fk_matches_ik<S: SixSix>(sys: &S, rng: &mut Rng) -> usize {
    let start = find_start(sys, HOME_LEGS, None).unwrap();
    let home = pose_from_unknowns(sys, start.v()).unwrap();
    assert!((home.handedness() - 1.0).abs() < 1e-9);
    let mut solved = 0;
    for _ in 0..20 {
        let e = home.euler();
        let pose = Pose::from_euler(
            e[0] + rng.uniform(-0.15, 0.15),
            e[1] + rng.uniform(-0.15, 0.15),
            e[2] + rng.uniform(-0.15, 0.15),
            std::array::from_fn(|i| home.translation[i] + rng.uniform(-15.0, 15.0)),
        );
        let (x, v) = legs_for_pose(sys, &pose).unwrap();
        let (_, flips) = linkage_tests::straight_path_truth(sys, &start, &x, 500);
        let sol = arc_length(sys, &start, &x, &Options::TIGHT).unwrap();
        if flips > 0 {
            assert!(!sol.is_ok());
            continue;
        }
        assert_eq!(sol.status, Status::Converged);
        assert!(max_diff(&sol.v, &v) < 1e-6, "{}", max_diff(&sol.v, &v));
        let p = pose_from_unknowns(sys, &sol.v).unwrap();
        assert!((p.handedness() - 1.0).abs() < 1e-9, "never mirrored");
        solved += 1;
    }
    solved
}

#[test]
fn any_six_six_geometry_solves_coplanar_or_not_and_never_mirrored() {
    let mut rng = Rng::new(11);
    let mut solved = 0;
    for (lift_platform, lift_base) in [(false, false), (false, true), (true, false), (true, true)] {
        for _ in 0..3 {
            let (base, platform) = random_geometry(&mut rng, lift_platform, lift_base);
            assert_eq!(platform_is_coplanar(&platform), !lift_platform);
            solved += if lift_platform {
                assert!(
                    Stewart::with_joints(&base, &platform).is_err(),
                    "the coplanar form refuses"
                );
                fk_matches_ik(
                    &StewartGeneral::with_joints(&base, &platform).unwrap(),
                    &mut rng,
                )
            } else {
                fk_matches_ik(&Stewart::with_joints(&base, &platform).unwrap(), &mut rng)
            };
        }
    }
    assert!(solved > 200, "{solved}");
}

#[test]
fn the_general_form_has_no_mirror_image_roots() {
    // A non-coplanar platform: its mirror image satisfies every distance but not Eq. 3's cross
    // product term.
    let mut rng = Rng::new(12);
    let (base, platform) = random_geometry(&mut rng, true, false);
    let sys = StewartGeneral::with_joints(&base, &platform).unwrap();
    let start = find_start(&sys, HOME_LEGS, None).unwrap();
    let mut mirrored = *start.v();
    for z in &mut mirrored[12..18] {
        *z = -*z;
    }
    let mut f = [0.0; 18];
    sys.residual(&mirrored, start.x(), &mut f);
    assert!(
        f[6..15].iter().any(|r| r.abs() > 1e-3),
        "a mirrored platform must violate the rigid-body rows"
    );
    // ... whereas the distances alone are preserved.
    assert!(f[15..].iter().all(|r| r.abs() < 1e-6));
}

#[test]
fn a_start_pose_that_does_not_fit_the_legs_is_refused() {
    let s = Stewart::new();
    let wrong = Pose::from_euler(0.3, 0.0, 0.0, [0.0, 0.0, 100.0]);
    assert_eq!(
        find_start(&s, HOME_LEGS, Some(wrong)).err(),
        Some(StartError::PoseMismatch)
    );
    let right = Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 159.011]);
    assert!(find_start(&s, HOME_LEGS, Some(right)).is_ok());
    assert!(matches!(
        find_start(&s, [-1.0; 6], None),
        Err(StartError::Solve(_))
    ));
}

#[test]
fn a_geometry_singular_everywhere_is_named_as_such() {
    // Legs 1 and 2 on the same base joint and the same platform joint: their two equations
    // have the same gradient at every configuration, so ∂F/∂v is never regular.
    let g = Stewart::new().geometry().to_owned();
    let joint = |at: usize, i: usize| -> [f64; 3] { std::array::from_fn(|a| g[at + 3 * i + a]) };
    let mut base: [[f64; 3]; 6] = std::array::from_fn(|i| joint(0, i));
    let mut platform: [[f64; 3]; 6] = std::array::from_fn(|i| joint(18, i));
    base[1] = base[0];
    platform[1] = platform[0];
    let singular = Stewart::with_joints(&base, &platform).unwrap();
    let err = find_start(&singular, HOME_LEGS, None).err();
    assert_eq!(err, Some(StartError::SingularEverywhere));
    assert!(err.unwrap().to_string().contains("architecture-singular"));
    // Only the coincidence does it: the same legs on Table III's joints have a start.
    assert!(find_start(&Stewart::new(), HOME_LEGS, None).is_ok());
}

//! The scales and symbols of units, checked by hand.

use super::*;

fn mm_deg() -> Units {
    Units {
        declared: true,
        length: Some(Length::Mm),
        angle: Some(Angle::Deg),
        mass: Some(Mass::Kg),
        force: Some(Force::N),
        time: None,
    }
}

#[test]
fn a_power_is_named_by_the_watt_where_its_units_make_one() {
    let with = |length, force, time| Units {
        declared: true,
        length: Some(length),
        angle: None,
        mass: None,
        force: Some(force),
        time: Some(time),
    };
    assert_eq!(Dim::POWER.symbol(&with(Length::M, Force::N, Time::S)), "W");
    assert_eq!(Dim::POWER.symbol(&with(Length::Mm, Force::N, Time::Ms)), "W");
    assert_eq!(Dim::POWER.symbol(&with(Length::M, Force::KN, Time::S)), "kW");
    assert_eq!(Dim::POWER.symbol(&with(Length::In, Force::N, Time::S)), "N·in/s");
    // Work is named by the joule; a torque, of the same exponents, keeps force x length.
    assert_eq!(Dim::ENERGY.symbol(&with(Length::M, Force::N, Time::S)), "J");
    assert_eq!(Dim::ENERGY.symbol(&with(Length::Mm, Force::N, Time::S)), "mJ");
    assert_eq!(Dim::ENERGY.symbol(&with(Length::M, Force::KN, Time::S)), "kJ");
    assert_eq!(Dim::ENERGY.symbol(&with(Length::Mm, Force::KN, Time::S)), "J");
    assert_eq!(Dim::ENERGY.symbol(&with(Length::In, Force::N, Time::S)), "N·in");
    assert_eq!(Dim::TORQUE.symbol(&with(Length::M, Force::N, Time::S)), "N·m");
    assert_eq!(Dim::ANGLE.generalised_force(), Dim::TORQUE);
    assert_eq!(Dim::ENERGY.over(Dim::TIME), Dim::POWER);
    assert_eq!(
        Dim::ENERGY.scale(&with(Length::Mm, Force::N, Time::S)),
        Dim::TORQUE.scale(&with(Length::Mm, Force::N, Time::S))
    );
}

#[test]
fn derived_units_are_written_from_their_kinds() {
    let u = mm_deg();
    assert_eq!(Dim::LENGTH.symbol(&u), "mm");
    assert_eq!(Dim::ANGLE.over(Dim::ANGLE).symbol(&u), "-");
    assert_eq!(Dim::LENGTH.over(Dim::ANGLE).symbol(&u), "mm/deg");
    assert_eq!(Dim::ANGLE.over(Dim::TIME).symbol(&u), "deg/s");
    assert_eq!(Dim::LENGTH.over(Dim::TIME.pow(2)).symbol(&u), "mm/s²");
    assert_eq!(Dim::ANGLE.generalised_force().symbol(&u), "N·mm");
    assert_eq!(Dim::LENGTH.generalised_force().symbol(&u), "N");
    assert_eq!(Dim::INERTIA.symbol(&u), "kg·mm²");
    assert_eq!(Dim::ANGLE.generalised_force().over(Dim::ANGLE).symbol(&u), "N·mm/deg");
    assert_eq!(Dim::LENGTH.over(Dim::ANGLE.times(Dim::ANGLE)).symbol(&u), "mm/deg²");
    assert_eq!(Dim::NONE.over(Dim::TIME).symbol(&u), "1/s");
    assert_eq!(Dim::LENGTH.over(Dim::ANGLE.times(Dim::TIME)).symbol(&u), "mm/(deg·s)");
    // A power is named by the watt where its size is one of the watt's multiples.
    assert_eq!(Dim::POWER.symbol(&u), "mW");
    assert_eq!(Dim::ENERGY.over(Dim::TIME).symbol(&u), "mW");
    // Without a UNITS line nothing is shown; a kind whose base unit is
    // not declared is not shown either.
    assert_eq!(Dim::ANGLE.symbol(&Units::NONE), "");
    let angle_only = Units { declared: true, angle: Some(Angle::Deg), ..Units::NONE };
    assert_eq!(Dim::ANGLE.symbol(&angle_only), "deg");
    assert_eq!(Dim::LENGTH.over(Dim::ANGLE).symbol(&angle_only), "");
    assert_eq!(Dim::TIME.symbol(&angle_only), "s");
    // Shown without UNITS: radians and seconds, nothing with a length.
    assert_eq!(Dim::ANGLE.over(Dim::TIME).shown(&Units::NONE), "rad/s");
    assert_eq!(Dim::ANGLE.over(Dim::ANGLE).shown(&Units::NONE), "-");
    assert_eq!(Dim::LENGTH.shown(&Units::NONE), "");
    assert_eq!(Dim::LENGTH.over(Dim::ANGLE).shown(&u), "mm/deg");
}

#[test]
fn scales_convert_to_si_and_back() {
    let u = mm_deg();
    assert_eq!(u.to_core(Dim::LENGTH, 250.0), 0.25);
    assert!((u.to_core(Dim::ANGLE, 180.0) - PI).abs() < 1e-15);
    // A torsion spring of 1 N·mm/deg is 180/pi * 1e-3 N·m/rad.
    let k = Dim::ANGLE.generalised_force().over(Dim::ANGLE);
    assert!((u.to_core(k, 1.0) - 1e-3 * 180.0 / PI).abs() < 1e-15);
    // An inertia of 1 kg·mm² is 1e-6 kg·m²; 1 g is 1e-3 kg; 1 kN 1000 N; 1 ms 1e-3 s.
    assert!((u.to_core(Dim::INERTIA, 1.0) - 1e-6).abs() < 1e-21);
    let other = Units {
        declared: true,
        mass: Some(Mass::G),
        force: Some(Force::KN),
        time: Some(Time::Ms),
        length: Some(Length::In),
        angle: None,
    };
    assert_eq!(other.to_core(Dim::MASS, 1.0), 1e-3);
    assert_eq!(other.to_core(Dim::FORCE, 2.0), 2e3);
    assert_eq!(other.to_core(Dim::TIME, 5.0), 5e-3);
    assert_eq!(other.to_core(Dim::LENGTH, 1.0), 0.0254);
    for d in [Dim::LENGTH, Dim::INERTIA, k, Dim::ENERGY.over(Dim::TIME)] {
        let back = u.from_core(d, u.to_core(d, 123.456));
        assert!((back - 123.456).abs() < 1e-12, "{d:?}");
    }
}

#[test]
fn a_number_given_in_the_models_units_is_written_back_as_given() {
    let inch = Units { length: Some(Length::In), mass: Some(Mass::G), ..mm_deg() };
    let k = Dim::ANGLE.generalised_force().over(Dim::ANGLE);
    let dims = [Dim::LENGTH, Dim::ANGLE, Dim::INERTIA, Dim::MASS, k, Dim::LENGTH.over(Dim::TIME)];
    // Numbers of up to three decimals, as a designer writes them (a seeded sweep).
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut drifted = 0;
    for _ in 0..5000 {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let (int, frac) = ((seed >> 40) % 100_000, (seed >> 20) % 1000);
        let sign = if seed & 1 == 0 { "" } else { "-" };
        let w: f64 = format!("{sign}{int}.{frac:03}").parse().unwrap();
        for units in [&mm_deg(), &inch] {
            for d in dims {
                let core = units.to_core(d, w);
                drifted += usize::from(units.from_core(d, core) != w);
                assert_eq!(units.as_written(d, core), w, "{w} {d:?}");
            }
        }
    }
    // The plain conversion back misses some of them: the sweep shows what `as_written` is for.
    assert!(drifted > 100, "{drifted}");
    // Without units a number is left as it is, bit for bit.
    for v in [0.1, -3.7e-300, f64::MAX, f64::NAN] {
        assert_eq!(Units::NONE.as_written(Dim::LENGTH, v).to_bits(), v.to_bits());
    }
}

#[test]
fn no_units_leave_every_number_as_it_is() {
    let u = Units::NONE;
    assert!(u.is_identity());
    for v in [0.1, -3.7e-300, f64::MAX] {
        assert_eq!(u.to_core(Dim::INERTIA, v).to_bits(), v.to_bits());
        assert_eq!(u.from_core(Dim::LENGTH.over(Dim::ANGLE), v).to_bits(), v.to_bits());
    }
    let si = Units { declared: true, length: Some(Length::M), angle: Some(Angle::Rad), ..Units::NONE };
    assert!(si.is_identity());
    assert!(!mm_deg().is_identity());
}

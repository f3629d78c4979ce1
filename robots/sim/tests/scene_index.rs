//! The scene's spatial grid answers exactly what a test of every solid in
//! list order answers: rays (nearest, ties to the first listed), footprint
//! overlaps, point tests and scan fans, over random walls, obstacles and
//! loose solids, with some switched off.

use ilmr_sim::geometry::{Circle, Obb, Scene, Shape, Solid, SolidRef};
use ilmr_sim::rng::Rng;
use ilmr_sim::{PlaneVector, Point2, Vector2};

fn scene(next: &mut impl FnMut() -> f64, n: usize, side: f64) -> Scene {
    let mut solids: Vec<Solid> = (0..n)
        .map(|i| {
            let c = Point2::new(side * next(), side * next());
            let (shape, what) = match i % 5 {
                0 => (
                    Shape::Circle(Circle::new(c, 0.05 + next())),
                    SolidRef::Obstacle(i),
                ),
                1 => (Shape::Circle(Circle::new(c, 0.3)), SolidRef::Target(i)),
                2 => (
                    Shape::Box(Obb::new(c, 7.0 * next(), 0.4, 0.3)),
                    SolidRef::PickupBox(i),
                ),
                // Walls long and short, on cell borders now and then.
                _ => {
                    let c = if i % 7 == 0 {
                        Point2::new((c.x / 2.0).round() * 2.0, c.y)
                    } else {
                        c
                    };
                    let len = 0.2 + 15.0 * next();
                    let h = if i % 3 == 0 { 0.0 } else { 7.0 * next() };
                    (
                        Shape::Box(Obb::new(c, h, len, 0.05 + 0.3 * next())),
                        SolidRef::Wall(i),
                    )
                }
            };
            let mut s = Solid::new(shape, what);
            s.active = i % 11 != 4;
            s
        })
        .collect();
    // A duplicate, so that rays tie.
    solids.push(solids[3].clone());
    Scene::new(solids)
}

#[test]
fn the_grid_answers_what_every_solid_answers() {
    let mut rng = Rng::new(12);
    let mut next = move || rng.uniform();
    let mut hits = 0;
    for round in 0..60 {
        let side = [20.0, 60.0, 200.0][round % 3];
        let s = scene(&mut next, 40 + round * 5, side);
        let all = s.solids().len();
        for _ in 0..300 {
            let o = Point2::new(side * (1.4 * next() - 0.2), side * (1.4 * next() - 0.2));
            let dir = Vector2::from_angle(7.0 * next());
            let range = [4.0, 30.0, 500.0][hits % 3];
            let want = s.ray_among(o, dir, range, 0..all);
            let got = s.ray(o, dir, range);
            assert_eq!(
                got.map(|h| (h.distance.to_bits(), h.what)),
                want.map(|h| (h.distance.to_bits(), h.what)),
                "round {round}"
            );
            hits += usize::from(want.is_some());
            let fp = Obb::new(o, 7.0 * next(), 1.2, 0.6);
            let want = s
                .solids()
                .iter()
                .filter(|x| x.active)
                .find(|x| x.shape.overlaps_box(&fp))
                .map(|x| x.what);
            assert_eq!(s.overlapping(&fp), want, "round {round}");
            let inside = s.solids().iter().any(|x| x.active && x.shape.contains(o));
            assert_eq!(s.contains(o), inside, "round {round}");
        }
        // A scan's fan meets what every solid meets.
        let o = Point2::new(side * next(), side * next());
        let (count, first) = (361, 7.0 * next());
        let step = std::f64::consts::PI / 360.0;
        let fan = s.fan(o, first, step, count, 30.0);
        for i in 0..count {
            let dir = Vector2::from_angle(first + i as f64 * step);
            let want = s.ray_among(o, dir, 30.0, 0..all);
            let got = fan.ray(&s, i, o, dir, 30.0);
            assert_eq!(
                got.map(|h| (h.distance.to_bits(), h.what)),
                want.map(|h| (h.distance.to_bits(), h.what)),
                "round {round}, beam {i}"
            );
        }
    }
    assert!(hits > 3000, "{hits}");
}

//! Micro-benchmarks: each primitive's spans along a ray, and span-list
//! combination. `cargo bench --bench spans`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use csgrt::csg::spans::{combine, Boundary, Span};
use csgrt::geometry::{Cone, Cuboid, Halfspace, Probe, Shape, Sphere, Torus};
use csgrt::math::boolean::Op;
use glam::DVec3;

/// Rays from a sphere of radius 4 towards points near the origin, in
/// object space (a fixed, deterministic set).
fn rays() -> Vec<(DVec3, DVec3)> {
    let mut s = 0x1234_5678_9abc_def0u64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..256)
        .map(|_| {
            let o = DVec3::new(next(), next(), next()).normalize_or(DVec3::X) * 4.0;
            let target = DVec3::new(next(), next(), next()) * 0.8;
            (o, target - o)
        })
        .collect()
}

fn primitives(c: &mut Criterion) {
    let rays = rays();
    let shapes = [
        ("sphere", Shape::Sphere(Sphere)),
        ("cube", Shape::Cuboid(Cuboid { centered: true })),
        (
            "cylinder",
            Shape::Cone(Cone {
                r0: 1.0,
                r1: 1.0,
                centered: true,
            }),
        ),
        (
            "cone",
            Shape::Cone(Cone {
                r0: 1.0,
                r1: 0.0,
                centered: true,
            }),
        ),
        ("torus", Shape::Torus(Torus { minor: 0.3 })),
        ("halfspace", Shape::Halfspace(Halfspace)),
    ];
    let mut g = c.benchmark_group("spans");
    for (name, shape) in shapes {
        g.bench_function(name, |b| {
            let mut st = csgrt::stats::Stats::default();
            b.iter(|| {
                let mut n = 0usize;
                for &(o, d) in &rays {
                    let mut q = Probe {
                        o: black_box(o),
                        d: black_box(d),
                        tmin: f64::NEG_INFINITY,
                        tmax: f64::INFINITY,
                        st: &mut st,
                        need: csgrt::geometry::Need::Spans,
                    };
                    shape.spans(&mut q, &mut |s| n += s.0 as usize & 1);
                }
                n
            })
        });
    }
    g.finish();
}

fn list(prim: u32, v: &[(f64, f64)]) -> Vec<Span> {
    let b = |t| Boundary::new(t, prim, 0);
    v.iter()
        .map(|&(x, y)| Span {
            enter: b(x),
            exit: b(y),
        })
        .collect()
}

fn combination(c: &mut Criterion) {
    let a = list(0, &[(0.0, 1.0), (2.0, 3.0), (4.0, 5.0)]);
    let b = list(1, &[(0.5, 2.5), (3.0, 4.0), (4.5, 9.0)]);
    let mut g = c.benchmark_group("combine");
    for (name, op) in [
        ("union", Op::Union),
        ("intersection", Op::Intersection),
        ("difference", Op::Difference),
    ] {
        g.bench_function(name, |bch| {
            bch.iter(|| combine(op, black_box(&a), black_box(&b), 0.0))
        });
    }
    g.finish();
}

criterion_group!(benches, primitives, combination);
criterion_main!(benches);

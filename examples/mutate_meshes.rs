//! A stable-toolchain stand-in for `cargo fuzz run mesh_*` where no
//! nightly is at hand: N mutants per format (bit flips, byte sets, cuts,
//! splices of the format's corpus) through the same harness, any panic
//! reported with the input saved under `fuzz/artifacts/`.
//!
//!     cargo run --release --example mutate_meshes -- 1000000

use std::panic;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100_000);
    panic::set_hook(Box::new(|_| {}));
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for &(dir, ext) in csgrt::harness::MESH_TARGETS {
        let corpus: Vec<Vec<u8>> = std::fs::read_dir(format!("fuzz/corpus/mesh_{dir}"))
            .expect("run from the repository root")
            .map(|e| std::fs::read(e.unwrap().path()).unwrap())
            .collect();
        let mut failed = 0;
        for _ in 0..n {
            let mut x = corpus[rnd() as usize % corpus.len()].clone();
            for _ in 0..1 + rnd() % 4 {
                let len = x.len().max(1);
                match rnd() % 5 {
                    0 if !x.is_empty() => x[rnd() as usize % len] ^= 1 << (rnd() % 8),
                    1 if !x.is_empty() => {
                        x[rnd() as usize % len] = b"0123456789 -.e\n#"[rnd() as usize % 16]
                    }
                    2 => x.truncate(rnd() as usize % (len + 1)),
                    3 => {
                        let other = &corpus[rnd() as usize % corpus.len()];
                        let at = rnd() as usize % (x.len() + 1);
                        let from = rnd() as usize % (other.len() + 1);
                        x.splice(at..at, other[from..].iter().take(64).copied());
                    }
                    _ => x.push(rnd() as u8),
                }
            }
            if panic::catch_unwind(|| csgrt::harness::exercise_mesh(ext, &x)).is_err() {
                failed += 1;
                std::fs::create_dir_all("fuzz/artifacts").unwrap();
                std::fs::write(format!("fuzz/artifacts/mesh_{dir}_{failed}"), &x).unwrap();
            }
        }
        println!("{ext}: {n} inputs, {failed} panics");
    }
}

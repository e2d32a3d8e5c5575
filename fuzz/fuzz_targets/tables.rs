//! The tabulated distributions (1D tables and their guide and Eytzinger forms, alias tables, 2D
//! tables) built from arbitrary weights, edges and domains, then queried at arbitrary `u` and at the
//! ends of `[0, 1)`. A constructor may refuse; what it accepts must sample: the index in range, never
//! a bin of weight 0, a point inside the support whose density is positive, finite and what `pdf`
//! says.
#![no_main]
use libfuzzer_sys::fuzz_target;
use rtl_sampling::{
    AliasPiecewise, AliasTable, EytzingerCdf, GuideTable, PiecewiseConstant2D, Sample, TabulatedCdf,
};

const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;

/// The input: a selector byte, then little-endian f64s (any bit pattern: NaN, subnormals, 1e308).
fn floats(data: &[u8]) -> Vec<f64> {
    data.chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// The `u` to query: the ends of `[0, 1)`, a few inside, and every input float folded into [0, 1).
fn queries(v: &[f64]) -> Vec<f64> {
    let mut u = vec![
        0.0,
        f64::MIN_POSITIVE,
        0.5,
        ONE_MINUS_EPSILON.next_down(),
        ONE_MINUS_EPSILON,
    ];
    u.extend(v.iter().map(|x| x.abs().fract()));
    u
}

fn check_1d(s: Sample, (a, b): (f64, f64), pdf: f64) {
    assert!(s.x >= a && s.x < b, "x = {} outside [{a}, {b})", s.x);
    assert!(
        s.pdf > 0.0 && s.pdf.is_finite(),
        "pdf {} at x = {}",
        s.pdf,
        s.x
    );
    assert_eq!(s.pdf, pdf, "sample and pdf disagree at x = {}", s.x);
}

fn tables_1d(v: &[f64], weights: &[f64], t: TabulatedCdf) {
    let dom = t.domain();
    let guide = GuideTable::new(t.clone()).expect("guide of a valid table");
    let eytz = EytzingerCdf::new(&t);
    for u in queries(v) {
        let bin = t.bin(u.min(ONE_MINUS_EPSILON));
        assert!(bin < weights.len(), "bin {bin} of {}", weights.len());
        assert!(
            weights[bin] > 0.0,
            "bin {bin} of weight 0 chosen at u = {u}"
        );
        let s = t.sample(u);
        check_1d(s, dom, t.pdf(s.x));
        let g = guide.sample(u);
        assert_eq!(g, s, "guide table differs at u = {u}");
        let e = eytz.sample(u);
        check_1d(e, dom, eytz.pdf(e.x));
        let back = t.invert(s.x);
        assert!((0.0..=1.0).contains(&back), "invert gives {back}");
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let v = floats(rest);
    match mode % 6 {
        0 if v.len() >= 2 => {
            let (a, b, w) = (v[0], v[1], &v[2..]);
            if let Ok(t) = TabulatedCdf::from_weights(a, b, w) {
                tables_1d(&v, w, t);
            }
        }
        1 => {
            // edges and weights interleaved: e0 w0 e1 w1 ... en
            let edges: Vec<f64> = v.iter().step_by(2).copied().collect();
            let w: Vec<f64> = v.iter().skip(1).step_by(2).copied().collect();
            if let Ok(t) = TabulatedCdf::from_edges_and_weights(&edges, &w) {
                tables_1d(&v, &w, t.clone());
                let alias = AliasPiecewise::new(&edges, &w).expect("alias of a valid table");
                let dom = t.domain();
                for u in queries(&v) {
                    let s = alias.sample(u);
                    check_1d(s, dom, alias.pdf(s.x));
                }
            }
        }
        2 => {
            let points: Vec<(f64, f64)> = v.chunks_exact(2).map(|p| (p[0], p[1])).collect();
            if let Ok(t) = TabulatedCdf::from_points(&points) {
                let w: Vec<f64> = (0..t.len()).map(|i| t.bin_probability(i)).collect();
                tables_1d(&v, &w, t);
            }
        }
        3 => {
            if let Ok(t) = AliasTable::new(&v) {
                for u in queries(&v) {
                    let (i, rest) = t.sample(u);
                    assert!(i < v.len() && v[i] > 0.0, "bin {i} chosen at u = {u}");
                    assert!(t.pmf(i) > 0.0, "bin {i} of pmf 0 chosen");
                    assert!((0.0..1.0).contains(&rest), "remapped u = {rest}");
                }
            }
        }
        4 if v.len() >= 4 => {
            // nx from the selector's neighbour bits; the weights after the domain
            let nx = 1 + (data.len() % 7);
            let w = &v[4..];
            let ny = w.len() / nx;
            let built = PiecewiseConstant2D::new(&w[..nx * ny], nx, ny, (v[0], v[1]), (v[2], v[3]));
            if let Ok(t) = built {
                let qs = queries(&v);
                for (k, &u1) in qs.iter().enumerate() {
                    let u2 = qs[(k * 7 + 3) % qs.len()];
                    let s = t.sample(u1, u2);
                    assert!(s.x >= v[0] && s.x < v[1] && s.y >= v[2] && s.y < v[3]);
                    assert!(s.pdf > 0.0 && s.pdf.is_finite(), "pdf {} at {s:?}", s.pdf);
                    assert_eq!(s.pdf, t.pdf(s.x, s.y), "sample and pdf disagree at {s:?}");
                }
            }
        }
        _ => {
            // counts that overflow: nx * ny > usize::MAX must be refused, not panic
            let n = v.first().map_or(0, |x| x.to_bits() as usize);
            let _ = PiecewiseConstant2D::new(&v, n, usize::MAX, (0.0, 1.0), (0.0, 1.0));
            let _ = PiecewiseConstant2D::new(&v, usize::MAX, n | 2, (0.0, 1.0), (0.0, 1.0));
        }
    }
});

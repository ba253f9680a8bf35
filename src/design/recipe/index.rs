//! Indices on the gear: the shorthands faceters write, and a tier's indices under the
//! design's symmetry.

/// The indices a recipe's `indices` text names on a gear of `gear` teeth:
/// - a list separated by spaces, commas or GemCad's hyphens (`3-9-15`, `03 09 15`, `3,9`);
/// - `a:b:c`, from `a` in steps of `b` through `c` (`0:12:96`; 0 and the tooth count are one
///   index);
/// - `i xN`: `i` and its turns by 1/N of the gear (`12 x8`: 12, 24, …, 96).
///
/// Numbers are returned as written (whole or not, in range or not: [`super::Recipe::build`]
/// says which are off the gear), deduplicated modulo the gear, in order.
///
/// ```
/// use facetlab::design::recipe::parse_indices;
/// assert_eq!(parse_indices("3-93", 96).unwrap(), vec![3.0, 93.0]);
/// assert_eq!(parse_indices("0:24:96", 96).unwrap(), vec![0.0, 24.0, 48.0, 72.0]);
/// assert_eq!(parse_indices("12 x4", 96).unwrap(), vec![12.0, 36.0, 60.0, 84.0]);
/// assert!(parse_indices("3:0:9", 96).is_err());
/// ```
pub fn parse_indices(text: &str, gear: u32) -> Result<Vec<f64>, String> {
    let g = f64::from(gear.max(1));
    let t = text.trim();
    let num = |s: &str| -> Result<f64, String> {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("`{s}` is not an index"))
    };
    let raw: Vec<f64> = if let Some((i, n)) = t.split_once(['x', 'X']) {
        let (i, n) = (num(i)?, num(n)?);
        if !(n >= 1.0 && n.fract() == 0.0 && n <= g) {
            return Err(format!(
                "`{t}`: the repeat count after x must be a whole number 1–{gear}"
            ));
        }
        (0..n as usize).map(|k| i + g * k as f64 / n).collect()
    } else if t.contains(':') {
        let parts: Vec<&str> = t.split(':').collect();
        if parts.len() != 3 {
            return Err(format!("`{t}`: a range is start:step:end"));
        }
        let (a, b, c) = (num(parts[0])?, num(parts[1])?, num(parts[2])?);
        if b.is_nan() || b <= 0.0 || (c - a) / b > 4.0 * g {
            return Err(format!(
                "`{t}`: the step must be positive and the range at most a few turns of the gear"
            ));
        }
        let mut v = Vec::new();
        let mut x = a;
        while x <= c + 1e-9 {
            v.push(x);
            x += b;
        }
        v
    } else {
        let parts: Vec<&str> = t
            .split(|c: char| c.is_whitespace() || c == ',' || c == '-')
            .filter(|s| !s.is_empty())
            .collect();
        if parts.is_empty() {
            return Err("no indices given".into());
        }
        parts.iter().map(|s| num(s)).collect::<Result<_, _>>()?
    };
    let mut out: Vec<f64> = Vec::new();
    for x in raw {
        if !out
            .iter()
            .any(|y| ((x - y).rem_euclid(g)).min((y - x).rem_euclid(g)) < 1e-9)
        {
            out.push(x);
        }
    }
    Ok(out)
}

/// `indices` and their images under `symmetry`-fold rotation and (with `mirror`) the mirror
/// about the line through `offset`, modulo the gear, sorted as GemCad lists them (index 0 as
/// the tooth count, first).
///
/// ```
/// use facetlab::design::recipe::symmetric_indices;
/// let mains = symmetric_indices(&[3.0], 96, 0.0, 8, true);
/// assert_eq!(mains.len(), 16);
/// assert_eq!(mains[..3], [3.0, 9.0, 15.0]);
/// assert_eq!(symmetric_indices(&[0.0], 96, 0.0, 4, false), vec![96.0, 24.0, 48.0, 72.0]);
/// ```
pub fn symmetric_indices(
    indices: &[f64],
    gear: u32,
    offset: f64,
    symmetry: u32,
    mirror: bool,
) -> Vec<f64> {
    let g = f64::from(gear.max(1));
    let s = symmetry.max(1);
    let mut all: Vec<f64> = Vec::new();
    let mut push = |x: f64| {
        let x = x.rem_euclid(g);
        let x = if x < 1e-9 || g - x < 1e-9 { 0.0 } else { x };
        if !all.iter().any(|y| (x - y).abs() < 1e-9) {
            all.push(x);
        }
    };
    for &i in indices {
        for k in 0..s {
            let r = i + g * f64::from(k) / f64::from(s);
            push(r);
            if mirror {
                push(2.0 * offset - r);
            }
        }
    }
    all.sort_by(f64::total_cmp);
    all.into_iter()
        .map(|x| if x == 0.0 { g } else { x })
        .collect()
}

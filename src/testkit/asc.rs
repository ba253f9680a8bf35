//! Test designs shared by the reader's, the writer's and the instructions' tests: a small
//! brilliant written cleanly and the hard way, a gear-80 design with every kind of metadata,
//! and a comparison of plane sets.

use crate::geometry::FacetPlane;

/// A small brilliant on a 96 gear: 16 girdle facets (tier named `G`), 8 pavilion mains,
/// 8 bezels, table, culet. Girdle radius 1 (GemCad units), girdle 0.06 thick at the mains.
pub(crate) const MINI: &str = "GemCad 5.0
g 96 0.0
y 8 y
I 2.42
H Mini brilliant
H test design
a -90.000000 1.000000 3 n G 9 15 21 27 33 39 45 51 57 63 69 75 81 87 93
a -41.000000 0.691553 96 n P 12 24 36 48 60 72 84 G Cut to a point
a 0.000000 -0.900000 96 n K G Small culet
a 34.000000 0.595019 96 n B 12 24 36 48 60 72 84 G Level girdle.
a 0.000000 0.332598 96 n T
F Footnote one
";

/// The same design the hard way: BOM, CRLF and a lone CR, a Windows-1252 en dash in a
/// title, glued `g96` and `a-41`, the girdle's index list wrapped over three lines, a
/// fractional table index, negative (counted back) and out-of-turn bezel indices, the culet as `a -0`,
/// unknown lines and blank lines, a repeated facet.
pub(crate) fn messy() -> Vec<u8> {
    let mut b: Vec<u8> =
        b"\xEF\xBB\xBFGemCad 5.0\r\ng96 0.0\r\ny8y\r\nI 2.42\r\nH Mini brilliant \x96 test\r\n"
            .to_vec();
    b.extend_from_slice(b"Hello world\r\n\r\nQ 1 2 3\r\n");
    b.extend_from_slice(
        b"a -90 1.0 3 n G 9 15 21\r\n   27 33 39 45 51 57\r\n63 69 75 81 87 93\r\n",
    );
    b.extend_from_slice(b"a-41.0 0.691553 96 n P 12 24 36 48 60 72 84 G Cut to a point\r");
    b.extend_from_slice(b"a -0 0.9 96 n K\r\n");
    b.extend_from_slice(b"a 34 0.595019 0 n B -84 24 36 48 60 72 -12\r\n");
    b.extend_from_slice(b"a -41.0 0.691553 12\r\n");
    b.extend_from_slice(b"a 0 0.332598 1.5 n T\r\n\r\nF Footnote one\r\n");
    b
}

pub(crate) fn same_planes(
    a: &[FacetPlane],
    b: &[FacetPlane],
    tol: f64,
) -> std::result::Result<(), String> {
    if a.len() != b.len() {
        return Err(format!("{} planes vs {}", a.len(), b.len()));
    }
    let mut used = vec![false; b.len()];
    for p in a {
        let hit = b.iter().enumerate().position(|(j, q)| {
            !used[j]
                && p.plane.normal.distance(q.plane.normal) < tol
                && (p.plane.offset - q.plane.offset).abs() < tol
        });
        match hit {
            Some(j) => used[j] = true,
            None => return Err(format!("no match for {} {:?}", p.name, p.plane)),
        }
    }
    Ok(())
}

/// A gear-80 design of our own with every kind of metadata GemCad writes.
pub(crate) const STAR80: &str = "GemCad 5.0
g 80 0.0
y 5 y
I 1.61
H Test Star 80
H by facetlab tests
a -41.000000 0.66000000 80 n P 16 32 48 64 G Cut to a point
a -90.000000 1.00000000 80 n G 16 32 48 64 8 24 40 56 72 G Size stone
a -43.000000 0.68000000 8 n Q 24 40 56 72 G Meet P, G
a 40.000000 0.80000000 80 n A 16 32 48 64 8 24 40 56 72 G Set girdle thickness
a 0.000000 0.55000000 80 n T
F Leave the table polished
";

//! Sweeps and grids: a score mapped over a config's parameters, the scores along one (a
//! profile), N-axis grids and their shards. A sweep scores the config's start cut with the
//! swept parameters changed, through the optimizer's [`Evaluator`](crate::optimize::Evaluator)
//! and its objective ([`crate::optimize::objective_of`]); it searches nothing, and nothing in
//! [`crate::optimize`] imports it. It draws no charts: the binary hands it the plot module's
//! ([`HeatmapChart`], [`ProfileChart`]).
//!
//! **Grids.** N-axis sweeps and their shards: the grid of any number of [`Axis`] values, its
//! fixed order, the share of it one shard evaluates, the shard's row file, and the exact merge.
//!
//! **Order.** The grid is the Cartesian product of the axes with the *first* axis varying
//! fastest (`--x`, then `--y`, then each `--axis` in order): point `i` has axis `a` at value
//! index `(i / (n_0 · … · n_{a−1})) mod n_a`. This is the order the 2-axis sweep has always
//! written (x fastest), so 1- and 2-axis CSVs are unchanged.
//!
//! **CSV.** `<axis keys…>,brilliance,fire,scintillation,objective` (+ the extra scores of the
//! first scored point), one row per grid point in grid order; `NaN` where the cut failed.
//!
//! **Shards.** Shard `K/N` (1-based K) evaluates the points `i` with `i mod N == K − 1`
//! (interleaved, so neighbouring — similarly slow — points spread over all shards). A shard
//! appends each finished point to `rows.csv` as one line
//! `index,<axis values…>,brilliance,fire,scintillation,objective,extras` where `extras` is
//! `-` for a cut that failed and otherwise `name=value;name=value` (possibly empty). Numbers are
//! written exactly as the sweep's CSV writes them (shortest round-trip), so a merge that reads
//! them back writes the same bytes as one unsharded run. `shard.rs` is the one writer and
//! reader of these lines ([`shard_row`], [`read_rows`]) and of a row by name
//! ([`GridCell::named`], [`GridCell::from_named`]: what the Python package's `Grid` hands out
//! and takes back).
//!
//! The files: `map.rs` holds the axes, the scores a sweep maps, the two-axis map ([`sweep()`],
//! [`write()`]) and the one-axis profile ([`profile()`], [`write_profile`]); `points.rs` the
//! grid, its evaluation and its CSV; `shard.rs` a shard's share, its row file, its record
//! (`shard.json`) and the merge's check that the shards cover the grid once; `resume.rs` a
//! shard run into its folder, resumably ([`ShardRun`]);
//! `slice.rs` the views of an N-axis grid (the axes mapped, the others held at
//! `--at` values): heatmaps and profiles.

mod map;
mod points;
mod resume;
mod shard;
mod slice;
#[cfg(test)]
mod tests;

// Sweeps: a score mapped over two parameters, or the scores along one (a profile).
pub use map::{
    output_paths, profile, run_path, sweep, write, write_profile, Axis, Cell, Heatmap,
    HeatmapChart, Point, Profile, ProfileChart, ProfileLines, Sweep, SweepScore,
};
// N-axis grids, their shards (`--shard K/N`, job arrays) and the exact merge.
pub use points::{best, evaluate, to_csv, Grid, GridCell};
pub use resume::{shard_folder, ShardRun};
pub use shard::{
    assemble, config_hash, read_rows, rows_header, shard_row, AxisRecord, Named, Shard, ShardRecord,
};
pub use slice::{fixed_at, map_axes, parse_at, MapSpec, Swept};

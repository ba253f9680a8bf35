use super::shard::parse_shard_row;
use super::*;
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::optimize::{Config, ScoreSet};

fn cfg() -> Config {
    Config::from_str(
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
        "s.toml",
    )
    .unwrap()
}

fn bump(cut: &Cut) -> Result<ScoreSet> {
    let (a, b) = (cut.params["crown_angle"], cut.params["pavilion_angle"]);
    if a == 35.0 && b == 40.0 {
        return Err(Error::Geometry("refused".into()));
    }
    let mut s = ScoreSet::new(
        (-((a - 34.0) / 2.0).powi(2) - (b - 40.5).powi(2)).exp(),
        cut.params["table"] / 3.0,
        0.1,
    );
    s.extra.push((crate::metrics::ScoreName::AsetRed, a / 7.0));
    Ok(s)
}

#[test]
fn order_shards_rows_and_merge_agree_with_the_two_axis_sweep() {
    let c = cfg();
    let x = Axis::parse("x axis", "crown_angle:33:36:1", &c).unwrap();
    let y = Axis::parse("y axis", "pavilion_angle:40:41:0.5", &c).unwrap();
    let t = Axis::parse("axis", "table:0.55:0.57:0.01", &c).unwrap();
    let two = Grid::new(vec![x.clone(), y.clone()]).unwrap();
    assert_eq!(two.point(5), vec![34.0, 40.5], "first axis fastest");
    let all: Vec<usize> = (0..two.len()).collect();
    let cells = evaluate(&c, &bump, &two, &all, None, &|_| {});
    let old = super::sweep(&c, &bump, &x, &y, None).unwrap();
    assert_eq!(
        to_csv(&two, &cells),
        old.to_csv(),
        "same bytes as the 2-axis sweep"
    );
    let one = Grid::new(vec![x.clone()]).unwrap();
    let p = super::profile(&c, &bump, &x, None).unwrap();
    let cells1 = evaluate(&c, &bump, &one, &[0, 1, 2, 3], None, &|_| {});
    assert_eq!(
        to_csv(&one, &cells1),
        p.to_csv(),
        "same bytes as the profile"
    );

    let three = Grid::new(vec![x.clone(), y.clone(), t]).unwrap();
    assert_eq!(three.len(), 36);
    assert_eq!(three.indices(23), vec![3, 2, 1]);
    assert_eq!(three.index(&[3, 2, 1]), 23);
    let all: Vec<usize> = (0..three.len()).collect();
    let cells = evaluate(&c, &bump, &three, &all, None, &|_| {});
    let whole = to_csv(&three, &cells);
    assert!(whole.starts_with("crown_angle,pavilion_angle,table,brilliance,"));
    // Three shards, their rows written and read back, merged: the same bytes.
    let mut rows = Vec::new();
    for k in 1..=3 {
        let s = Shard { k, n: 3 };
        let mut text = rows_header(&three);
        for i in s.indices(three.len()) {
            assert!(s.owns(i));
            text.push_str(&shard_row(&cells[i]));
        }
        text.push_str("17,3"); // cut short by an interruption
        let (back, len) = read_rows(&text, &three).unwrap();
        assert_eq!(len, text.len() - 4);
        rows.extend(back.into_iter().map(|c| (format!("shard {k}"), c)));
    }
    let merged = assemble(&three, rows.clone()).unwrap();
    assert_eq!(to_csv(&three, &merged), whole);
    let mut dup = rows.clone();
    dup.push(("shard 9".into(), rows[0].1.clone()));
    assert!(assemble(&three, dup).unwrap_err().contains("shard 9"));
    rows.pop();
    assert!(assemble(&three, rows).unwrap_err().contains("1 of 36"));
    // A map of any two axes with the third held.
    let labels: Vec<String> = three.axes.iter().map(|a| a.label()).collect();
    let fixed = fixed_at(&three, &[("crown_angle".into(), 34.2)]).unwrap();
    assert_eq!(fixed, vec![1, 1, 1]);
    let swept = Swept {
        grid: &three,
        cells: &cells,
        labels: &labels,
    };
    let m = swept.heatmap(&SweepScore::FIRE, (1, 2), &fixed, "t".into(), None);
    assert_eq!((m.xs.len(), m.ys.len()), (3, 3));
    assert!((m.z[2][0] - 0.57 / 3.0).abs() < 1e-12);
    assert!(fixed_at(&three, &[("table".into(), 0.9)]).is_err());
    assert!(map_axes(&three, Some("table,nope")).is_err());
    assert_eq!(
        map_axes(&three, Some("table,crown_angle")).unwrap(),
        vec![2, 0]
    );
}

#[test]
fn shards_parse_and_come_from_job_arrays() {
    assert_eq!(Shard::parse("shard", "2/3").unwrap(), Shard { k: 2, n: 3 });
    for bad in ["0/3", "4/3", "3", "a/b", "1/0"] {
        assert!(Shard::parse("shard", bad)
            .unwrap_err()
            .to_string()
            .starts_with("shard:"));
    }
    let env = |pairs: &'static [(&'static str, &'static str)]| {
        move |k: &str| {
            pairs
                .iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    };
    let slurm = env(&[
        ("SLURM_ARRAY_TASK_ID", "5"),
        ("SLURM_ARRAY_TASK_MIN", "4"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
    ]);
    assert_eq!(
        Shard::from_env(&slurm).unwrap().unwrap().0,
        Shard { k: 2, n: 3 }
    );
    let k8s = env(&[("JOB_COMPLETION_INDEX", "0"), ("JOB_COMPLETION_COUNT", "4")]);
    assert_eq!(
        Shard::from_env(&k8s).unwrap().unwrap().0,
        Shard { k: 1, n: 4 }
    );
    let half = env(&[("JOB_COMPLETION_INDEX", "0")]);
    assert!(Shard::from_env(&half).is_err());
    assert!(Shard::from_env(&env(&[])).unwrap().is_none());
    assert_eq!(Shard { k: 2, n: 3 }.indices(8), vec![1, 4, 7]);
    assert_eq!(config_hash(b"a"), "af63dc4c8601ec8c");
}

#[test]
fn a_row_by_name_is_the_row_rows_csv_holds_and_comes_back_whole() {
    let c = cfg();
    let x = Axis::parse("x axis", "crown_angle:34:35:1", &c).unwrap();
    let y = Axis::parse("y axis", "pavilion_angle:40:40.5:0.5", &c).unwrap();
    let grid = Grid::new(vec![x, y]).unwrap();
    let all: Vec<usize> = (0..grid.len()).collect();
    let mut cells = evaluate(&c, &bump, &grid, &all, None, &|_| {});
    assert!(
        cells[1].scores.is_none(),
        "crown 35, pavilion 40 is refused"
    );
    // A score that is not finite is written as NaN: by name too.
    cells[2].scores.as_mut().unwrap().fire = f64::INFINITY;
    for cell in &cells {
        let line = shard_row(cell);
        let read = parse_shard_row(line.trim_end(), &grid).unwrap();
        let (fixed, extras) = cell.named(&grid);
        assert_eq!(
            format!("{:?}", read.named(&grid)),
            format!("{:?}", (fixed.clone(), extras.clone()))
        );
        let keys: Vec<&str> = fixed.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(
            format!("index,{},extras\n", keys.join(",")),
            rows_header(&grid),
            "the names are the header's"
        );
        assert_eq!(extras.is_some(), cell.scores.is_some());
        // Back from the names, in any order: the same line.
        let mut values: Vec<(String, f64)> = fixed.into_iter().rev().collect();
        values.extend(extras.clone().into_iter().flatten());
        let back = GridCell::from_named(&grid, cell.index, extras.is_some(), &values).unwrap();
        assert_eq!(shard_row(&back), line);
    }
    let (fixed, _) = cells[0].named(&grid);
    assert_eq!(fixed[0], ("crown_angle".to_string(), 34.0));
    assert_eq!(fixed[3].0, "fire");
    let without: Vec<(String, f64)> = fixed.iter().filter(|(k, _)| k != "fire").cloned().collect();
    let e = GridCell::from_named(&grid, 0, true, &without).unwrap_err();
    assert_eq!(e, "a row has no `fire`");
    let mut odd = fixed.clone();
    odd.push(("sparkle".into(), 1.0));
    let e = GridCell::from_named(&grid, 0, true, &odd).unwrap_err();
    assert_eq!(e, "`sparkle` is not a score");
    let e = GridCell::from_named(&grid, 4, true, &fixed).unwrap_err();
    assert_eq!(e, "index 4 is not a point of the grid (0 to 3)");
}

//! Log–log plots of the work–precision runs, with plotters (SVG).

use crate::Run;
use plotters::prelude::*;
use std::path::Path;

pub enum Work {
    Time,
    Evals,
}

const COLORS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

fn bounds(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let lo = values.clone().fold(f64::INFINITY, f64::min);
    let hi = values.fold(0.0, f64::max);
    (lo / 2.0, hi * 2.0)
}

/// Error against work, one line per method, log–log.
pub fn work_precision(
    path: &Path,
    system: &str,
    runs: &[&Run],
    work: Work,
) -> Result<(), Box<dyn std::error::Error>> {
    let x = |r: &Run| match work {
        Work::Time => r.wall_seconds,
        Work::Evals => r.rhs_evals as f64,
    };
    let floor = 1e-16;
    let runs: Vec<&Run> = runs.iter().copied().filter(|r| x(r) > 0.0).collect();
    let (x0, x1) = bounds(runs.iter().map(|r| x(r)));
    let (y0, y1) = bounds(runs.iter().map(|r| r.error.max(floor)));
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let xlabel = match work {
        Work::Time => "wall time [s] (median of runs)",
        Work::Evals => "right-hand-side evaluations",
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "{system}: error against {}",
                xlabel.split(' ').next().unwrap_or("")
            ),
            ("sans-serif", 22),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc("error at the final time")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    let mut methods: Vec<&str> = runs.iter().map(|r| r.method).collect();
    methods.dedup();
    for (k, method) in methods.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let points: Vec<(f64, f64)> = runs
            .iter()
            .filter(|r| r.method == *method)
            .map(|r| (x(r), r.error.max(floor)))
            .collect();
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
            .label(*method)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart.draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p, 3, color.filled())),
        )?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Relative energy error against time (in orbits), log–log.
pub fn energy_over_time(
    path: &Path,
    curves: &[(String, Vec<(f64, f64)>)],
) -> Result<(), Box<dyn std::error::Error>> {
    let all = curves.iter().flat_map(|(_, c)| c.iter());
    let (x0, x1) = bounds(all.clone().map(|p| p.0));
    let (y0, y1) = bounds(all.map(|p| p.1));
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Kepler e = 0.6: worst energy error per orbit, 1000 orbits",
            ("sans-serif", 22),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time [orbits]")
        .y_desc("|E - E0| / |E0|")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    for (k, (name, points)) in curves.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

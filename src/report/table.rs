//! A table defined once: each column's name, unit and type with its values. The CSV writer
//! prints it, and a front end (the Python package) takes its arrays at full precision, so
//! the file and the arrays cannot differ in columns, order or types: slide's loading.csv,
//! events.csv and advances.csv, slide --dynamics' dyn_events.csv, fronts_t.csv and
//! summary.csv, converge's convergence.csv, sweep's sweep.csv, rupture's station files and
//! stability's five study files are built this way.

use super::finite;
use crate::error::Result;
use std::borrow::Cow;
use std::fmt::Write as _;

/// A column's values: whole numbers, numbers (NaN: no value, an empty CSV cell where the
/// column allows it) or text.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    Int(Vec<i64>),
    Float(Vec<f64>),
    /// Whole numbers that may not exist for a row (None: an empty cell), e.g. a count of a
    /// run that was not made.
    MaybeInt(Vec<Option<i64>>),
    Text(Vec<String>),
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::Int(v) => v.len(),
            Values::Float(v) => v.len(),
            Values::MaybeInt(v) => v.len(),
            Values::Text(v) => v.len(),
        }
    }
}

/// How a column's numbers are printed where it does not follow its table's digits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Scientific notation with this many significant digits.
    Sci(usize),
    /// The shortest decimal that reads back as the same number (Rust's `{}`): the paper's
    /// iteration, whose values are exact fractions of its inputs.
    Shortest,
    /// The shortest scientific notation that reads back as the same number (`{:e}`).
    ShortestSci,
    /// This many decimals (wall times, s).
    Fixed(usize),
    /// Text in double quotes (a message that may hold commas; its own double quotes written
    /// as single ones), an empty text an empty cell.
    Quoted,
}

/// One column: its CSV name, its unit (SI, `1` for a dimensionless ratio, `-` for a count,
/// code or label) and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// Built at run time where a table has a column per rule (fig5_fe.csv).
    pub name: Cow<'static, str>,
    pub unit: &'static str,
    /// NaN is written as an empty cell (a quantity that does not exist for the row); where
    /// false, a non-finite value is refused (a bug, never written).
    pub may_be_empty: bool,
    /// The column's own format, where it differs from the table's digits (sweep.csv's edge
    /// widths: 7 significant digits of 13).
    pub format: Option<Format>,
    pub values: Values,
}

impl Column {
    fn new(
        name: impl Into<Cow<'static, str>>,
        unit: &'static str,
        may_be_empty: bool,
        values: Values,
    ) -> Column {
        Column { name: name.into(), unit, may_be_empty, format: None, values }
    }
    pub fn int(name: impl Into<Cow<'static, str>>, unit: &'static str, v: Vec<i64>) -> Column {
        Column::new(name, unit, false, Values::Int(v))
    }
    pub fn float(name: impl Into<Cow<'static, str>>, unit: &'static str, v: Vec<f64>) -> Column {
        Column::new(name, unit, false, Values::Float(v))
    }
    /// A number that may not exist for a row (NaN: an empty cell).
    pub fn maybe(name: impl Into<Cow<'static, str>>, unit: &'static str, v: Vec<f64>) -> Column {
        Column::new(name, unit, true, Values::Float(v))
    }
    /// A whole number that may not exist for a row (None: an empty cell).
    pub fn maybe_int(name: impl Into<Cow<'static, str>>, unit: &'static str, v: Vec<Option<i64>>) -> Column {
        Column::new(name, unit, true, Values::MaybeInt(v))
    }
    pub fn text(name: impl Into<Cow<'static, str>>, unit: &'static str, v: Vec<String>) -> Column {
        Column::new(name, unit, false, Values::Text(v))
    }
    /// The column printed with `digits` significant digits instead of the table's.
    pub fn with_digits(self, digits: usize) -> Column {
        self.with_format(Format::Sci(digits))
    }
    /// The column printed in `format` instead of the table's digits.
    pub fn with_format(self, format: Format) -> Column {
        Column { format: Some(format), ..self }
    }
}

/// A table: its columns, of equal length, and the significant digits its numbers are
/// printed with.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub columns: Vec<Column>,
    pub digits: usize,
}

impl Table {
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, |c| c.values.len())
    }

    /// The CSV text: the names, then one line per row; numbers in scientific notation with
    /// [`Self::digits`] significant digits (or in the column's own [`Format`]).
    pub fn csv(&self) -> Result<String> {
        let n = self.rows();
        debug_assert!(self.columns.iter().all(|c| c.values.len() == n), "ragged table");
        let mut s = self.columns.iter().map(|c| c.name.as_ref()).collect::<Vec<_>>().join(",");
        s.push('\n');
        for i in 0..n {
            for (j, c) in self.columns.iter().enumerate() {
                if j > 0 {
                    s.push(',');
                }
                match &c.values {
                    Values::Int(v) => write!(s, "{}", v[i]).unwrap(),
                    Values::MaybeInt(v) => {
                        if let Some(k) = v[i] {
                            write!(s, "{k}").unwrap()
                        }
                    }
                    Values::Text(v) if c.format == Some(Format::Quoted) && !v[i].is_empty() => {
                        write!(s, "\"{}\"", v[i].replace('"', "'")).unwrap()
                    }
                    Values::Text(v) => s.push_str(&v[i]),
                    Values::Float(v) if c.may_be_empty && !v[i].is_finite() => {}
                    Values::Float(v) => {
                        let x = finite(&c.name, v[i])?;
                        match c.format.unwrap_or(Format::Sci(self.digits)) {
                            Format::Sci(d) => write!(s, "{:.*e}", d.saturating_sub(1), x),
                            Format::Shortest => write!(s, "{x}"),
                            Format::ShortestSci => write!(s, "{x:e}"),
                            Format::Fixed(d) => write!(s, "{x:.d$}"),
                            Format::Quoted => write!(s, "\"{x}\""),
                        }
                        .unwrap()
                    }
                }
            }
            s.push('\n');
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_prints_types_digits_and_empty_cells() {
        let t = Table {
            columns: vec![
                Column::int("event", "-", vec![3, 7]),
                Column::text("kind", "-", vec!["slip".into(), "open".into()]),
                Column::float("X_m", "m", vec![1.0 / 3.0, -2.5e-7]),
                Column::maybe("t_s", "s", vec![f64::NAN, 0.125]),
                Column::maybe_int("n", "-", vec![Some(4), None]),
                Column::float("w", "1", vec![2.0, 1.0 / 3.0]).with_digits(3),
                Column::text("why", "-", vec!["p < 0, \"opens\"".into(), String::new()])
                    .with_format(Format::Quoted),
            ],
            digits: 10,
        };
        assert_eq!(
            t.csv().unwrap(),
            "event,kind,X_m,t_s,n,w,why\n3,slip,3.333333333e-1,,4,2.00e0,\"p < 0, 'opens'\"\n7,open,-2.500000000e-7,1.250000000e-1,,3.33e-1,\n"
        );
        // A column that must hold a number refuses NaN, naming itself.
        let bad = Table { columns: vec![Column::float("X_m", "m", vec![f64::NAN])], digits: 10 };
        assert!(bad.csv().unwrap_err().to_string().contains("X_m"));
    }
}

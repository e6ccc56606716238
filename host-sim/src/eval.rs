//! `host-sim eval`: the eval protocol of `docs/eval-protocol.md` (the models are defined in
//! `docs/models.md`).
//!
//! JSON Lines on standard input, one JSON line per input line on standard output, in the same
//! order. Every model id and its parameters are listed once, in [`MODELS`]: the table that
//! `--list-models` prints, that checks each line's keys, and that the dispatch [`eval_model`]
//! (generic over [`arealight::Real`], instantiated per backend) reads its parameters through.
//!
//! Behaviour the protocol leaves open, decided here (and documented in `docs/eval-protocol.md`):
//!
//! - a blank (empty or whitespace-only) input line is skipped: it gets no output line, but it
//!   counts for the input line numbers of error messages;
//! - a line that is not a JSON object, or has no `id`, gets an error line that starts with its
//!   input line number (`input line 3: ...`); when the JSON is broken but an `id` can be read
//!   from its beginning, that `id` is echoed;
//! - keys other than `id`, `model` and the model's parameters are an error on that line (with
//!   a suggestion when one is a near miss), as are missing parameters (all of them named at
//!   once);
//! - an id the protocol does not define answers `unknown model: ...` (with a suggestion) on
//!   every backend;
//! - range checks the backends must agree on (sigma, alpha, m) are made in f64, before the
//!   conversion to the backend's scalar type; a finite number too large for f32 (say 1e300) is
//!   refused on the f32 backends as not fitting f32;
//! - the exit status is 0 whenever input and output work (the protocol's rule), even when some
//!   lines got an error; then one summary line goes to standard error.

use std::io::{self, BufRead, Write};

use arealight::{
    CapLight, Fast32, Fixed22, HemisphereLight, OvercastSky, PhongLobe, PolygonLight, Real, Rgb,
    Sh9, SkyGround, SphereLight, Vec3, WorldPoint, WorldPolygonLight, WorldSphereLight,
};
use clap::{Args, ValueEnum};
use serde::Serialize;
use serde_json::{Map, Value};

mod dispatch;
mod models;
mod params;
pub use dispatch::*;
pub use models::*;
pub use params::*;

/// The polygon capacity of the protocol (more vertices: the library's `TooManyVertices`).
pub const MAX_VERTICES: usize = 64;

/// The scalar backend the library is instantiated with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// The reference: the library's generic code with T = f64.
    #[value(name = "f64")]
    F64,
    /// The firmware float path: T = f32 (libm).
    #[value(name = "f32")]
    F32,
    /// T = arealight::Fast32: f32 with the library's cheap sqrt and atan2.
    #[value(name = "f32-fast")]
    F32Fast,
    /// The fixed-point path: T = arealight::Fixed22 (I10F22), for the models marked "fixed"
    /// by --list-models; the others answer "unsupported".
    #[value(name = "fixed")]
    Fixed,
}

/// Arguments of `host-sim eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Scalar backend to evaluate with.
    #[arg(long, value_enum, default_value = "f64")]
    pub backend: Backend,
    /// Print every model id with its parameters (name, type, range) and the backends that
    /// answer it, then exit without reading standard input.
    #[arg(long)]
    pub list_models: bool,
}

/// The candidate closest to `word` when it is a near miss (a typo, a missing suffix), else
/// `None`: optimal string alignment distance (case-insensitive) at most a third of the
/// word's length (at least 1, less than the whole word), or `word` a prefix of the candidate
/// of 3 characters or more.
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let w: Vec<char> = word.to_lowercase().chars().collect();
    let limit = (w.len() / 3).max(1);
    let mut best: Option<(usize, &'a str)> = None;
    for c in candidates {
        let cl = c.to_lowercase();
        let d = if w.len() >= 3 && cl.starts_with(&word.to_lowercase()) {
            1
        } else {
            distance(&w, &cl.chars().collect::<Vec<_>>())
        };
        if d <= limit && d < w.len() && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

/// Optimal string alignment distance (insertions, deletions, substitutions, adjacent
/// transpositions).
fn distance(a: &[char], b: &[char]) -> usize {
    let (n, m) = (a.len(), b.len());
    let mut d = vec![vec![0usize; m + 1]; n + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, x) in d[0].iter_mut().enumerate() {
        *x = j;
    }
    for i in 1..=n {
        for j in 1..=m {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut x = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                x = x.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = x;
        }
    }
    d[n][m]
}

/// ` (did you mean x?)` or nothing.
pub fn did_you_mean<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    closest(word, candidates).map_or(String::new(), |c| format!(" (did you mean {c}?)"))
}

/// The answer of a model: a scalar or an RGB triple, already converted to f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Answer {
    /// `{"value": x}`.
    Value(f64),
    /// `{"rgb": [r, g, b]}`.
    Rgb([f64; 3]),
}

/// Why a line has no value: the text of its `error` field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EvalError(pub String);

impl From<arealight::Error> for EvalError {
    fn from(e: arealight::Error) -> Self {
        EvalError(e.to_string())
    }
}
impl From<String> for EvalError {
    fn from(s: String) -> Self {
        EvalError(s)
    }
}
impl From<&str> for EvalError {
    fn from(s: &str) -> Self {
        EvalError(s.to_owned())
    }
}

type EvalResult<T> = Result<T, EvalError>;

/// One output line; `id` comes first.
#[derive(Debug, Serialize)]
pub struct OutLine {
    id: Value,
    #[serde(skip_serializing_if = "Option::is_none")]
    value: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rgb: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
    /// A remark about the input that does not change the answer (keys the model does not
    /// take): printed on standard error, never on the output line.
    #[serde(skip)]
    warning: Option<String>,
}

impl OutLine {
    fn error(id: Value, msg: impl Into<String>) -> Self {
        OutLine {
            id,
            value: None,
            rgb: None,
            error: Some(msg.into()),
            warning: None,
        }
    }

    /// The warning about this line's input, if any (see [`OutLine`]).
    pub fn warning(&self) -> Option<&str> {
        self.warning.as_deref()
    }

    /// Whether this is an error line.
    pub fn is_error(&self) -> bool {
        self.error.is_some()
    }
}

/// Every parameter of the model is there, else an error naming all the missing ones and the
/// model's parameters. Keys that are not `id`, `model` or a parameter do not change the answer
/// (the protocol does not forbid them): they come back as a warning naming them, with
/// suggestions.
fn check_keys(def: &ModelDef, map: &Map<String, Value>) -> EvalResult<Option<String>> {
    let takes = format!("{} takes {}", def.id, def.param_names());
    let absent: Vec<&str> = def
        .params
        .iter()
        .map(|p| p.name)
        .filter(|n| !map.contains_key(*n))
        .collect();
    let unknown: Vec<String> = map
        .keys()
        .filter(|k| !matches!(k.as_str(), "id" | "model") && def.param(k).is_none())
        .map(|k| format!("{k}{}", did_you_mean(k, def.params.iter().map(|p| p.name))))
        .collect();
    let s = |n: usize| if n == 1 { "" } else { "s" };
    if !absent.is_empty() {
        // A misspelt parameter shows as missing: name the unknown keys too, with suggestions.
        let also = if unknown.is_empty() {
            String::new()
        } else {
            format!("; unknown: {}", unknown.join(", "))
        };
        return Err(EvalError(format!(
            "missing parameter{}: {} ({takes}){also}",
            s(absent.len()),
            absent.join(", ")
        )));
    }
    Ok((!unknown.is_empty()).then(|| {
        format!(
            "unknown parameter{} for {}, ignored: {}; {takes}",
            s(unknown.len()),
            def.id,
            unknown.join(", ")
        )
    }))
}

/// Calls `f(param, x)` for every number of the real-valued parameters (integers `m`, `k`
/// excluded) of the line.
fn each_number(
    def: &ModelDef,
    map: &Map<String, Value>,
    f: &mut dyn FnMut(&'static str, f64) -> EvalResult<()>,
) -> EvalResult<()> {
    fn walk(
        v: &Value,
        name: &'static str,
        f: &mut dyn FnMut(&'static str, f64) -> EvalResult<()>,
    ) -> EvalResult<()> {
        match v {
            Value::Array(a) => a.iter().try_for_each(|x| walk(x, name, f)),
            Value::Number(_) | Value::String(_) => f(name, number(v, name)?),
            _ => Ok(()),
        }
    }
    for p in def.params.iter().filter(|p| p.kind != Kind::Integer) {
        if let Some(v) = map.get(p.name) {
            walk(v, p.name, f)?;
        }
    }
    Ok(())
}

/// A finite number that the backend's scalar type cannot hold (above 3.4e38 for the f32
/// backends) is refused as such, instead of becoming infinity and "not finite".
fn inputs_fit<T: Real>(def: &ModelDef, map: &Map<String, Value>) -> EvalResult<()> {
    each_number(def, map, &mut |name, x| {
        if x.is_finite() && !T::from_f64(x).to_f64().is_finite() {
            Err(EvalError(format!(
                "{name}: {x:e} does not fit f32 (largest finite f32: {:e})",
                f32::MAX
            )))
        } else {
            Ok(())
        }
    })
}

/// The fixed-point type cannot hold NaN, infinities or magnitudes of 512 and more: such an
/// input gets the error the float backends give for a non-finite value, or a range error,
/// instead of a silently saturated value. The positions of [`WORLD_MODELS`] are world
/// coordinates, whose range (`|x| < 2^30`) [`arealight::WorldPoint`] checks.
fn fixed_inputs_representable(def: &ModelDef, map: &Map<String, Value>) -> EvalResult<()> {
    let world = WORLD_MODELS.contains(&def.id);
    each_number(def, map, &mut |name, x| {
        if !x.is_finite() {
            Err(arealight::Error::NotFinite(name).into())
        } else if world && WORLD_PARAMS.contains(&name) {
            // World coordinates: their own range (2^30), checked by `WorldPoint`.
            Ok(())
        } else if x.abs() >= 512.0 {
            Err(EvalError(format!(
                "{name} is outside the range of the fixed-point backend (|x| < 512)"
            )))
        } else {
            Ok(())
        }
    })
}

/// The `id` of a line that is not valid JSON, when its beginning reads as an object whose
/// members up to `"id": value` are well formed (a truncated line, a typo after the id).
fn salvage_id(line: &[u8]) -> Option<Value> {
    fn skip_ws(line: &[u8], mut i: usize) -> usize {
        while line.get(i).is_some_and(u8::is_ascii_whitespace) {
            i += 1;
        }
        i
    }
    /// One JSON value at `line[i..]` and the offset after it.
    fn value<T: serde::de::DeserializeOwned>(line: &[u8], i: usize) -> Option<(T, usize)> {
        let mut it = serde_json::Deserializer::from_slice(line.get(i..)?).into_iter::<T>();
        let v = it.next()?.ok()?;
        Some((v, i + it.byte_offset()))
    }
    let mut i = skip_ws(line, 0);
    if line.get(i) != Some(&b'{') {
        return None;
    }
    i += 1;
    loop {
        let (key, after) = value::<String>(line, i)?;
        i = skip_ws(line, after);
        if line.get(i) != Some(&b':') {
            return None;
        }
        let (v, after) = value::<Value>(line, i + 1)?;
        if key == "id" {
            return (!v.is_null()).then_some(v);
        }
        i = skip_ws(line, after);
        if line.get(i) != Some(&b',') {
            return None;
        }
        i += 1;
    }
}

/// serde_json's message without its position (`... at line 1 column 40`), and the column.
fn json_error(e: &serde_json::Error) -> String {
    let msg = e.to_string();
    let text = match msg.rsplit_once(" at line ") {
        Some((text, _)) => text.to_owned(),
        None => msg,
    };
    format!("{text} at column {}", e.column())
}

/// Answers one non-blank input line, number `line_no` (1-based, blank lines counted) of the
/// input.
pub fn process_line(line: &[u8], line_no: usize, backend: Backend) -> OutLine {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    let line = line.strip_suffix(b"\r").unwrap_or(line);
    let parsed: Value = match serde_json::from_slice(line) {
        Ok(v) => v,
        Err(e) => {
            return OutLine::error(
                salvage_id(line).unwrap_or(Value::Null),
                format!("input line {line_no}: invalid JSON: {}", json_error(&e)),
            )
        }
    };
    let Value::Object(map) = parsed else {
        return OutLine::error(
            Value::Null,
            format!("input line {line_no}: a line must be a JSON object"),
        );
    };
    let id = match map.get("id") {
        None | Some(Value::Null) => {
            return OutLine::error(
                Value::Null,
                format!("input line {line_no}: missing parameter: id"),
            )
        }
        Some(id) => id.clone(),
    };
    let model = match map.get("model") {
        Some(Value::String(m)) => m.as_str(),
        Some(other) => {
            return OutLine::error(id, format!("model: expected a string, got {}", kind(other)))
        }
        None => return OutLine::error(id, "missing parameter: model"),
    };
    let Some(def) = find_model(model) else {
        let hint = did_you_mean(model, MODELS.iter().map(|m| m.id));
        return OutLine::error(
            id,
            format!("unknown model: {model}{hint}; `host-sim eval --list-models` lists them"),
        );
    };
    if backend == Backend::Fixed && !def.fixed() {
        return OutLine::error(
            id,
            format!("unsupported: the fixed-point backend does not implement {model}"),
        );
    }
    let params = Params::new(&map, def);
    let mut warning = None;
    let result = check_keys(def, &map).map(|w| warning = w);
    let result = result.and_then(|()| match backend {
        Backend::F64 => eval_model::<f64>(def, &params),
        Backend::F32 => inputs_fit::<f32>(def, &map).and_then(|()| eval_model::<f32>(def, &params)),
        Backend::F32Fast => {
            inputs_fit::<Fast32>(def, &map).and_then(|()| eval_model::<Fast32>(def, &params))
        }
        Backend::Fixed => {
            fixed_inputs_representable(def, &map).and_then(|()| eval_model::<Fixed22>(def, &params))
        }
    });
    match result {
        Ok(Answer::Value(x)) => OutLine {
            id,
            value: Some(x),
            rgb: None,
            error: None,
            warning,
        },
        Ok(Answer::Rgb(c)) => OutLine {
            id,
            value: None,
            rgb: Some(c),
            error: None,
            warning,
        },
        Err(EvalError(msg)) => OutLine {
            warning,
            ..OutLine::error(id, msg)
        },
    }
}

/// What a run answered: how many lines, how many of them errors, the first error's input
/// line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Summary {
    /// Output lines written (non-blank input lines).
    pub answered: usize,
    /// Of which error lines.
    pub errors: usize,
    /// The input line number of the first error line.
    pub first_error: Option<usize>,
}

impl Summary {
    /// The one line printed on standard error after a run with error lines.
    pub fn message(&self) -> Option<String> {
        let first = self.first_error?;
        Some(format!(
            "host-sim eval: {} of {} lines answered with an error (the first is input line {first}); exit status 0",
            self.errors, self.answered
        ))
    }
}

/// Runs the protocol from `input` to `output` until end of input. Blank lines are skipped.
///
/// # Errors
/// An I/O error reading the input or writing the output (a closed pipe among them).
pub fn run(input: impl BufRead, output: impl Write, backend: Backend) -> io::Result<Summary> {
    let mut input = input;
    let mut out = io::BufWriter::new(output);
    let mut buf = Vec::new();
    let mut summary = Summary::default();
    let mut line_no = 0;
    loop {
        buf.clear();
        if input.read_until(b'\n', &mut buf)? == 0 {
            break;
        }
        line_no += 1;
        if buf.iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        let line = process_line(&buf, line_no, backend);
        if let Some(w) = line.warning() {
            eprintln!("host-sim eval: input line {line_no}: {w}");
        }
        summary.answered += 1;
        if line.is_error() {
            summary.errors += 1;
            summary.first_error.get_or_insert(line_no);
        }
        serde_json::to_writer(&mut out, &line).map_err(io::Error::from)?;
        out.write_all(b"\n")?;
    }
    out.flush()?;
    Ok(summary)
}

/// `host-sim eval`: stdin to stdout, or `--list-models`. A closed output pipe ends the run
/// quietly. Exit status 0 unless input or output fails (the protocol's rule); a run with
/// error lines prints one summary line on standard error.
pub fn main(args: &EvalArgs) -> std::process::ExitCode {
    if args.list_models {
        print!("{}", list_models());
        return std::process::ExitCode::SUCCESS;
    }
    let stdin = io::stdin();
    let stdout = io::stdout();
    match run(stdin.lock(), stdout.lock(), args.backend) {
        Ok(summary) => {
            if let Some(msg) = summary.message() {
                eprintln!("{msg}");
            }
            std::process::ExitCode::SUCCESS
        }
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("host-sim eval: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(backend: Backend, line: &str) -> String {
        serde_json::to_string(&process_line(line.as_bytes(), 7, backend)).unwrap()
    }

    #[test]
    fn id_comes_first_and_numbers_round_trip() {
        let s = eval(
            Backend::F64,
            r#"{"id":"a","model":"hemi_const","n":[0,0,1],"axis":[0,0,1]}"#,
        );
        assert_eq!(s, r#"{"id":"a","value":1.0}"#);
        let s = eval(Backend::F64, r#"{"model":"hemi_const"}"#);
        assert_eq!(
            s,
            r#"{"id":null,"error":"input line 7: missing parameter: id"}"#
        );
    }

    #[test]
    fn exponent_parsing() {
        let def = find_model("phong_hemi_cos").unwrap();
        let m = |v: &str| {
            let map: Map<String, Value> = serde_json::from_str(&format!(r#"{{"m":{v}}}"#)).unwrap();
            Params::new(&map, def).uint("m")
        };
        assert_eq!(m("3"), Ok(3));
        assert_eq!(m("3.0"), Ok(3));
        assert_eq!(m("0"), Ok(0));
        assert_eq!(m("-0.0"), Ok(0));
        assert_eq!(m("1e30"), Ok(u32::MAX));
        let bad = Err(EvalError("m must be a non-negative integer".into()));
        assert_eq!(m("2.5"), bad);
        assert_eq!(m("-1"), bad);
        assert!(m(r#""NaN""#).unwrap_err().0.contains("not finite"));
        assert!(m(r#""Infinity""#).unwrap_err().0.contains("not finite"));
        let map: Map<String, Value> = serde_json::from_str(r#"{"m":256}"#).unwrap();
        let e = Params::new(&map, def).exponent::<Fixed22>("m").unwrap_err();
        assert_eq!(
            e.0,
            "Phong exponent m is too large: 256 > 255, the largest this backend accepts"
        );
        assert_eq!(Params::new(&map, def).exponent::<f32>("m"), Ok(256));
    }

    #[test]
    fn range_checks_agree_across_backends() {
        // Just above pi/2 in f64, but rounds to f32's pi/2.
        let line = r#"{"id":1,"model":"cap_lambert","n":[0,0,1],"axis":[0,0,1],"sigma":1.5707963267948968}"#;
        for b in [Backend::F64, Backend::F32, Backend::F32Fast] {
            assert!(eval(b, line).contains("sigma is outside"), "{b:?}");
        }
    }

    #[test]
    fn the_table_is_the_dispatch() {
        // The exponent limit the table states is the library's.
        assert_eq!(arealight::phong::MAX_EXPONENT, 1_048_576);
        assert_eq!(<Fixed22 as Real>::MAX_PHONG_EXPONENT, 255);
        // Ids are unique, and the fixed backend's list names only ids of the table.
        for (i, m) in MODELS.iter().enumerate() {
            assert!(MODELS[..i].iter().all(|o| o.id != m.id), "{}", m.id);
        }
        for id in FIXED_SUPPORTED.iter().chain(FIXED_SUPPORTED_MORE) {
            assert!(find_model(id).is_some(), "{id}");
        }
        // That the dispatch reads exactly the declared parameters is checked end to end
        // (tests/eval/: every model's line as the protocol lists it answers, and a read of
        // an undeclared name panics in debug builds).
    }

    #[test]
    fn suggestions() {
        let ids = || MODELS.iter().map(|m| m.id);
        assert_eq!(closest("cap_lambrt", ids()), Some("cap_lambert"));
        assert_eq!(closest("phong_sphre", ids()), Some("phong_sphere"));
        assert_eq!(closest("hemi_cosine", ids()), Some("hemi_cos"));
        assert_eq!(closest("no_such_model", ids()), None);
        assert_eq!(closest("fov", ["eye", "fov_deg"]), Some("fov_deg"));
        assert_eq!(closest("sigmaa", ["n", "axis", "sigma"]), Some("sigma"));
        assert_eq!(closest("x", ["n", "axis"]), None);
    }

    #[test]
    fn broken_lines_keep_their_id() {
        assert_eq!(
            salvage_id(br#"{"id":"c","model":"cap_lambert","n":[0,0,1]"#),
            Some(Value::from("c"))
        );
        assert_eq!(
            salvage_id(br#" { "model" : "x", "id" : 42 , "n": [0,"#),
            Some(Value::from(42))
        );
        assert_eq!(salvage_id(br#"{"model":"x","n":[0,0"#), None);
        assert_eq!(salvage_id(br#"{"id": nul"#), None);
        assert_eq!(salvage_id(b"not json"), None);
        let s = eval(
            Backend::F64,
            "{\"id\":\"c\",\"model\":\"cap_lambert\",\"n\":[0,0,1]\n",
        );
        assert_eq!(
            s,
            r#"{"id":"c","error":"input line 7: invalid JSON: EOF while parsing an object at column 43"}"#
        );
    }
}

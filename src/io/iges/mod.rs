//! IGES 5.3: rational B-spline surfaces (entity 128) with their transformation matrices (124)
//! applied exactly ([`surface`]); trimmed surfaces (144, 142) and B-rep faces (186, 514, 510,
//! 508, 504, 502) as faces with exact trimming loops in the surfaces' parameter planes
//! ([`trim`], [`brep`]), from the curves of [`curve`]. A face whose loops use curves limn does
//! not read yet, or have model-space curves only, is used untrimmed and reported; other surface
//! types are reported and skipped, never dropped silently.
//!
//! Records are 80 columns; column 73 names the section (S, G, D, P, T). Parameter data is in
//! columns 1-64 of the P records. Numbers may use Fortran `D` exponents; strings are Hollerith
//! (`5HHello`).

mod brep;
mod curve;
mod surface;
mod trim;

use super::{Place, ReadError};
use crate::io::trimmed::{self, DomainFailure, SurfaceInfo};
use crate::model::{Face, Format, Model, ModelPatch, PatchSource, Warning};
use crate::number::{parse_exact, Rational};
use std::collections::BTreeMap;

/// One directory entry (two D records).
#[derive(Clone, Debug)]
struct DirEntry {
    kind: i64,
    param_start: usize,
    transform: usize,
    param_lines: usize,
    form: i64,
}

/// An exact affine map x -> R x + T: (R, T).
type Affine = ([[Rational; 3]; 3], [Rational; 3]);

struct Reader<'a> {
    name: &'a str,
    pd: char,
    rd: char,
    dir: BTreeMap<usize, DirEntry>,
    /// P records by sequence number: their columns 1-64.
    params: Vec<String>,
    warnings: Vec<Warning>,
    /// Bézier control points the surfaces read so far split into.
    bezier_points: usize,
    /// The minimum resolution the global section states (field 19).
    resolution: Option<Rational>,
}

fn err_line(name: &str, line: usize, msg: impl Into<String>) -> ReadError {
    ReadError::new(name, Place::Line(line), msg)
}

/// Splits a parameter string into fields at `pd`, ending at `rd`; Hollerith strings are kept
/// whole (their text may contain delimiters).
fn split_fields(s: &str, pd: char, rd: char) -> Result<Vec<String>, String> {
    let chars: Vec<char> = s.chars().collect();
    let mut fields = Vec::new();
    let mut i = 0;
    loop {
        // Skip leading blanks.
        while i < chars.len() && chars[i] == ' ' {
            i += 1;
        }
        let start = i;
        while i < chars.len() && chars[i].is_ascii_digit() {
            i += 1;
        }
        if i > start && i < chars.len() && chars[i] == 'H' {
            let n: usize = chars[start..i]
                .iter()
                .collect::<String>()
                .parse()
                .map_err(|_| "bad Hollerith length".to_string())?;
            let text_start = i + 1;
            let end = text_start
                .checked_add(n)
                .filter(|&e| e <= chars.len())
                .ok_or_else(|| {
                    format!("a Hollerith string of {n} characters runs past the end of the data")
                })?;
            fields.push(chars[text_start..end].iter().collect());
            i = end;
            while i < chars.len() && chars[i] == ' ' {
                i += 1;
            }
        } else {
            while i < chars.len() && chars[i] != pd && chars[i] != rd {
                i += 1;
            }
            fields.push(
                chars[start..i]
                    .iter()
                    .collect::<String>()
                    .trim()
                    .to_string(),
            );
        }
        match chars.get(i) {
            Some(c) if *c == pd => i += 1,
            Some(c) if *c == rd => return Ok(fields),
            Some(c) => return Err(format!("unexpected {c:?} after a field")),
            None => {
                return Err("the parameter data has no record delimiter (truncated?)".to_string())
            }
        }
    }
}

/// Reads the delimiter in G field 1 or 2: `1Hx`, or nothing (the default).
fn read_delimiter(chars: &[char], i: &mut usize, default: char, pd: char) -> Result<char, String> {
    if chars.get(*i) == Some(&'1') && chars.get(*i + 1) == Some(&'H') {
        let c = *chars.get(*i + 2).ok_or("truncated delimiter")?;
        *i += 3;
        Ok(c)
    } else if chars.get(*i) == Some(&pd) || chars.get(*i) == Some(&';') {
        Ok(default)
    } else {
        Err("the global section must start with the parameter delimiter (1H, or ,)".to_string())
    }
}

pub(super) fn read(name: &str, bytes: &[u8]) -> Result<Model, ReadError> {
    // IGES is ASCII; any other byte is kept as the Latin-1 character of that value.
    let text: String = bytes.iter().map(|&b| b as char).collect();
    let mut g = String::new();
    let mut d_lines: Vec<(usize, String)> = Vec::new();
    let mut params = Vec::new();
    let mut seen_t = false;
    for (i, raw) in text.split('\n').enumerate() {
        let line_no = i + 1;
        let line = raw.trim_end_matches('\r');
        if line.trim().is_empty() {
            continue;
        }
        if line.chars().count() < 73 {
            return Err(err_line(
                name,
                line_no,
                format!("IGES records are 80 columns with the section letter in column 73; this one has {}", line.chars().count()),
            ));
        }
        let chars: Vec<char> = line.chars().collect();
        let body: String = chars[..72].iter().collect();
        match chars[72] {
            'S' => {}
            'G' => g.push_str(&body),
            'D' => d_lines.push((line_no, body)),
            'P' => params.push(chars[..64].iter().collect::<String>()),
            'T' => seen_t = true,
            c => {
                return Err(err_line(
                    name,
                    line_no,
                    format!("unknown section letter {c:?} in column 73"),
                ))
            }
        }
    }
    if d_lines.is_empty() {
        return Err(ReadError::new(
            name,
            Place::File,
            "no directory entry section (D records): not an IGES file, or truncated",
        ));
    }
    let mut warnings = Vec::new();
    if !seen_t {
        warnings.push(Warning {
            place: "file".into(),
            message: "no terminate (T) record: the file may be truncated".into(),
        });
    }
    // Global section: delimiters and the minimum resolution (field 19).
    let gchars: Vec<char> = g.chars().collect();
    let mut gi = 0;
    let gerr = |m: String| ReadError::new(name, Place::Named("global section".into()), m);
    let pd = read_delimiter(&gchars, &mut gi, ',', ',').map_err(gerr)?;
    if gchars.get(gi) == Some(&pd) {
        gi += 1;
    }
    let rd = read_delimiter(&gchars, &mut gi, ';', pd).map_err(gerr)?;
    let rest: String = gchars[gi..].iter().collect();
    let gfields = if rest.starts_with(rd) {
        Vec::new()
    } else {
        let rest = rest.strip_prefix(pd).unwrap_or(&rest);
        split_fields(rest, pd, rd).map_err(gerr)?
    };
    // gfields[0] is G field 3; field 19 (minimum resolution) is gfields[16].
    let resolution = gfields
        .get(16)
        .and_then(|s| parse_exact(s).ok())
        .filter(|r| r.cmp0() == std::cmp::Ordering::Greater);

    // Directory: pairs of D records.
    if d_lines.len() % 2 != 0 {
        let (l, _) = d_lines[d_lines.len() - 1];
        return Err(err_line(
            name,
            l,
            "the directory section has an odd number of records (each entry is two)",
        ));
    }
    let mut dir = BTreeMap::new();
    for (k, pair) in d_lines.chunks_exact(2).enumerate() {
        let seq = 2 * k + 1;
        let (line_no, first) = &pair[0];
        let (_, second) = &pair[1];
        let field = |s: &str, n: usize| -> String {
            s.chars()
                .skip(8 * n)
                .take(8)
                .collect::<String>()
                .trim()
                .to_string()
        };
        let int = |s: &str, n: usize, what: &str| -> Result<i64, ReadError> {
            let f = field(s, n);
            if f.is_empty() {
                return Ok(0);
            }
            f.parse::<i64>().map_err(|_| {
                err_line(
                    name,
                    *line_no,
                    format!("directory entry {seq}: {what} is {f:?}, not an integer"),
                )
            })
        };
        let kind = int(first, 0, "the entity type")?;
        let param_start = int(first, 1, "the parameter data pointer")?;
        let transform = int(first, 6, "the transformation matrix pointer")?;
        let param_lines = int(second, 3, "the parameter line count")?;
        let form = int(second, 4, "the form number")?;
        if param_start < 0 || param_lines < 0 {
            return Err(err_line(
                name,
                *line_no,
                format!("directory entry {seq}: negative parameter pointer or count"),
            ));
        }
        dir.insert(
            seq,
            DirEntry {
                kind,
                param_start: param_start as usize,
                transform: transform.max(0) as usize,
                param_lines: param_lines as usize,
                form,
            },
        );
    }
    let mut r = Reader {
        name,
        pd,
        rd,
        dir,
        params,
        warnings,
        bezier_points: 0,
        resolution,
    };
    r.read_model()
}

impl Reader<'_> {
    fn entity_err(&self, de: usize, msg: impl Into<String>) -> ReadError {
        let kind = self.dir.get(&de).map_or(0, |e| e.kind);
        ReadError::new(self.name, Place::Entity { de, kind }, msg)
    }

    fn warn(&mut self, de: usize, message: String) {
        let kind = self.dir.get(&de).map_or(0, |e| e.kind);
        self.warnings.push(Warning {
            place: format!("entity {kind} at directory entry {de}"),
            message,
        });
    }

    /// The parameter fields of an entity, after its type number.
    fn fields(&self, de: usize) -> Result<Vec<String>, ReadError> {
        let e = &self.dir[&de];
        let start = e.param_start;
        if e.param_lines == 0 {
            return Err(self.entity_err(de, "the directory entry gives 0 parameter data records"));
        }
        // The last P record of the entity (param_lines >= 1).
        let end = start.saturating_add(e.param_lines - 1);
        if start == 0 || end > self.params.len() {
            return Err(self.entity_err(
                de,
                format!(
                    "parameter data at P records {start}..={end} is outside the {} P records",
                    self.params.len()
                ),
            ));
        }
        let data: String = self.params[start - 1..end].concat();
        let fields = split_fields(&data, self.pd, self.rd).map_err(|m| self.entity_err(de, m))?;
        let kind: i64 = fields.first().and_then(|f| f.parse().ok()).unwrap_or(-1);
        if kind != e.kind {
            return Err(self.entity_err(
                de,
                format!(
                    "parameter data starts with type {:?}, not {}",
                    fields.first().map_or("", String::as_str),
                    e.kind
                ),
            ));
        }
        Ok(fields[1..].to_vec())
    }

    /// Follows a pointer to a directory entry, which must exist.
    fn pointer(&self, from: usize, value: &str, what: &str) -> Result<usize, ReadError> {
        let p: i64 = value
            .trim()
            .parse()
            .map_err(|_| self.entity_err(from, format!("{what}: {value:?} is not a pointer")))?;
        let p = p.unsigned_abs() as usize;
        if !self.dir.contains_key(&p) {
            return Err(self.entity_err(
                from,
                format!("{what}: pointer {p} names no directory entry"),
            ));
        }
        Ok(p)
    }

    /// The affine map of an entity's transformation chain: x -> R x + T, exact.
    fn transform(&self, de: usize) -> Result<Option<Affine>, ReadError> {
        let mut current = self.dir[&de].transform;
        let mut total: Option<Affine> = None;
        let mut depth = 0;
        while current != 0 {
            depth += 1;
            if depth > 64 {
                return Err(self.entity_err(
                    de,
                    "the chain of transformation matrices is longer than 64 (a cycle?)",
                ));
            }
            let t = self.dir.get(&current).ok_or_else(|| {
                self.entity_err(
                    de,
                    format!("transformation matrix pointer {current} names no directory entry"),
                )
            })?;
            if t.kind != 124 {
                return Err(self.entity_err(de, format!("transformation matrix pointer {current} names an entity of type {}, not 124", t.kind)));
            }
            let f = self.fields(current)?;
            if f.len() < 12 {
                return Err(self.entity_err(
                    current,
                    format!(
                        "a transformation matrix needs 12 numbers, found {}",
                        f.len()
                    ),
                ));
            }
            let mut v = Vec::with_capacity(12);
            for (i, s) in f[..12].iter().enumerate() {
                v.push(parse_exact(s).map_err(|e| {
                    self.entity_err(current, format!("matrix entry {}: {e}", i + 1))
                })?);
            }
            let r: [[Rational; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|j| v[4 * i + j].clone()));
            let tr: [Rational; 3] = std::array::from_fn(|i| v[4 * i + 3].clone());
            // The entity's own matrix applies first, then the one it points to.
            total = Some(match total {
                None => (r, tr),
                Some((r0, t0)) => {
                    let rr = std::array::from_fn(|i| {
                        std::array::from_fn(|j| {
                            (0..3)
                                .map(|k| Rational::from(&r[i][k] * &r0[k][j]))
                                .sum::<Rational>()
                        })
                    });
                    let tt = std::array::from_fn(|i| {
                        (0..3)
                            .map(|k| Rational::from(&r[i][k] * &t0[k]))
                            .sum::<Rational>()
                            + &tr[i]
                    });
                    (rr, tt)
                }
            });
            current = t.transform;
        }
        Ok(total)
    }

    /// Field `i` of an entity's fields `f` as an exact number.
    fn number(&self, de: usize, f: &[String], i: usize, what: &str) -> Result<Rational, ReadError> {
        let s = f.get(i).ok_or_else(|| {
            self.entity_err(
                de,
                format!("{what}: the parameter data ends early ({} fields)", f.len()),
            )
        })?;
        parse_exact(s).map_err(|e| self.entity_err(de, format!("{what}: {e}")))
    }

    /// `n` numbers from field `*i` on, named `what 1`, `what 2`, …; `*i` moves past them.
    fn numbers(
        &self,
        de: usize,
        f: &[String],
        i: &mut usize,
        n: usize,
        what: &str,
    ) -> Result<Vec<Rational>, ReadError> {
        let v = (*i..*i + n)
            .map(|k| self.number(de, f, k, &format!("{what} {}", k - *i + 1)))
            .collect();
        *i += n;
        v
    }

    /// Field `i` as a count, a whole number in `0..=max`.
    fn count(
        &self,
        de: usize,
        f: &[String],
        i: usize,
        what: &str,
        max: usize,
    ) -> Result<usize, ReadError> {
        let q = self.number(de, f, i, what)?;
        match q.is_integer().then(|| q.numer().to_usize()).flatten() {
            Some(n) if n <= max => Ok(n),
            _ => Err(self.entity_err(
                de,
                format!(
                    "{what}: {:?} is not a count (a whole number 0..={max})",
                    f[i].trim()
                ),
            )),
        }
    }

    /// Field `i` as a pointer to an existing directory entry (`None` for 0 when `optional`).
    fn pointer_at(
        &self,
        de: usize,
        f: &[String],
        i: usize,
        what: &str,
        optional: bool,
    ) -> Result<Option<usize>, ReadError> {
        let v = f.get(i).ok_or_else(|| {
            self.entity_err(
                de,
                format!("{what}: the parameter data ends early ({} fields)", f.len()),
            )
        })?;
        if optional && matches!(v.trim(), "" | "0") {
            return Ok(None);
        }
        self.pointer(de, v, what).map(Some)
    }

    /// Entity type of a directory entry (which exists).
    fn kind(&self, de: usize) -> i64 {
        self.dir[&de].kind
    }

    /// An error at `from` unless the entity `p` that its field `what` points to is of type
    /// `kind` (named `name`).
    fn expect_kind(
        &self,
        from: usize,
        p: usize,
        kind: i64,
        what: &str,
        name: &str,
    ) -> Result<(), ReadError> {
        if self.kind(p) == kind {
            return Ok(());
        }
        Err(self.entity_err(
            from,
            format!(
                "{what}: pointer {p} names an entity of type {}, not {name} ({kind})",
                self.kind(p)
            ),
        ))
    }

    fn read_model(&mut self) -> Result<Model, ReadError> {
        let entries: Vec<(usize, DirEntry)> =
            self.dir.iter().map(|(k, v)| (*k, v.clone())).collect();
        let mut model = Model::from_patches(Format::Iges, Vec::new());
        // Surfaces by directory entry: their number and parameter domain.
        let mut surfaces: BTreeMap<usize, SurfaceInfo> = BTreeMap::new();
        let mut skipped: BTreeMap<i64, usize> = BTreeMap::new();
        for (de, e) in &entries {
            match e.kind {
                128 => {
                    let index = surfaces.len();
                    let (info, pieces) = self.read_surface(*de, index)?;
                    for (span, patch) in pieces {
                        model.patches.push(ModelPatch {
                            surface: patch,
                            source: PatchSource::of_span(index, Some(*de), span, &info.spans),
                        });
                    }
                    surfaces.insert(*de, info);
                }
                108 | 114 | 118 | 120 | 122 | 140 | 190..=199 => {
                    *skipped.entry(e.kind).or_default() += 1
                }
                _ => {}
            }
        }
        model.left_out = skipped.values().sum();
        for (kind, n) in skipped {
            self.warnings.push(Warning {
                place: "file".into(),
                message: format!("{n} surface(s) of type {kind} are not rational B-spline surfaces (128) and are skipped"),
            });
        }
        if surfaces.is_empty() {
            return Err(ReadError::new(
                self.name,
                Place::File,
                "no rational B-spline surface (entity 128) in the file",
            ));
        }
        // Faces: trimmed surfaces and B-rep faces.
        // Faces not read as trimmed, by what is said of them.
        let mut untrimmed: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        let mut brep = brep::BrepBuilder::default();
        let mut shells = 0;
        for (de, e) in &entries {
            let (ptr_field, what) = match e.kind {
                144 => (0, "trimmed surface"),
                143 => (1, "bounded surface"),
                510 => (0, "face"),
                514 => {
                    shells += 1;
                    continue;
                }
                _ => continue,
            };
            let f = self.fields(*de)?;
            let s = self
                .pointer_at(*de, &f, ptr_field, "surface", false)?
                .expect("required");
            let Some(info) = surfaces.get(&s).cloned() else {
                let skind = self.kind(s);
                untrimmed
                    .entry(format!("{what}(s) on surfaces of type {skind}, not rational B-spline surfaces (128): skipped with their surfaces"))
                    .or_default()
                    .push(*de);
                if e.kind == 510 {
                    // Its loops still count in the B-rep's topology.
                    let _counted = self.brep_face(*de, None, &mut brep)?;
                }
                continue;
            };
            let face = match e.kind {
                144 => self.trimmed_surface(*de, s, &info)?,
                510 => self.brep_face(*de, Some(&info), &mut brep)?,
                _ => Err("bounded surfaces (143) are not read yet".to_string()),
            };
            let face = match face {
                Ok(face) => self.check_in_domain(face, &info)?,
                Err(why) => Err(why),
            };
            match face {
                Ok(face) => model.faces.push(face),
                Err(why) => untrimmed
                    .entry(format!("face(s) used untrimmed: {why}"))
                    .or_default()
                    .push(*de),
            }
        }
        if brep.faces > 0 {
            model.brep = Some(brep.finish(shells));
        }
        for (why, des) in untrimmed {
            let list: Vec<String> = des.iter().take(8).map(usize::to_string).collect();
            let more = if des.len() > 8 { ", …" } else { "" };
            let entries = if des.len() == 1 { "entry" } else { "entries" };
            self.warnings.push(Warning {
                place: format!("directory {entries} {}{more}", list.join(", ")),
                message: format!("{} {why}", des.len()),
            });
        }
        if !model.faces.is_empty() {
            let loops: usize = model.faces.iter().map(|f| f.loops().count()).sum();
            self.warnings.push(Warning {
                place: "file".into(),
                message: format!(
                    "{} trimmed face(s) with {loops} loop(s) read (see `limn info`): silhouettes and parabolic curves are clipped to them",
                    model.faces.len()
                ),
            });
        }
        model.surfaces = surfaces.len();
        model.warnings = std::mem::take(&mut self.warnings);
        model.suggested_weld = self.resolution.clone();
        Ok(model)
    }

    /// The face, when every curve of its loops lies in the surface's parameter domain or
    /// outside it by no more than the loop tolerance ([`trimmed::check_in_domain`]).
    fn check_in_domain(
        &self,
        face: Face,
        info: &SurfaceInfo,
    ) -> Result<Result<Face, String>, ReadError> {
        match trimmed::check_in_domain(&face, info) {
            Ok(()) => Ok(Ok(face)),
            Err(DomainFailure::AcrossSeam(why)) => Ok(Err(why)),
            Err(DomainFailure::Outside {
                entity, message, ..
            }) => Err(self.entity_err(entity.or(face.entity).unwrap_or(0), message)),
        }
    }
}

/// `x -> R x + T` applied to a point, exact.
fn apply(map: &Option<Affine>, p: &[Rational]) -> Vec<Rational> {
    match map {
        None => p.to_vec(),
        Some((r, t)) => (0..3)
            .map(|a| {
                (0..3)
                    .map(|b| Rational::from(&r[a][b] * &p[b]))
                    .sum::<Rational>()
                    + &t[a]
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::split_fields;

    #[test]
    fn fields_with_hollerith_and_fortran_exponents() {
        let f = split_fields("128,3HA,B,1.0D0, -2.5 ,,7;", ',', ';').unwrap();
        assert_eq!(f, vec!["128", "A,B", "1.0D0", "-2.5", "", "7"]);
        assert!(split_fields("128,99Habc;", ',', ';').is_err());
        assert!(split_fields("128,1,2", ',', ';').is_err());
    }
}

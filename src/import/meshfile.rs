//! Mesh files for `import()`: STL (ASCII and binary), OFF, OBJ and 3MF,
//! read into points and faces with every coordinate as the file gives it.
//!
//! STL and OFF are read here: the crates for them (`stl_io`, `off-rs`)
//! keep coordinates in f32, which moves an ASCII file's points by up to
//! 6·10⁻⁸ of their size, while OpenSCAD reads them as doubles; both
//! formats are a few lines of text or fixed records. STL follows
//! OpenSCAD 2021.01's `import_stl.cc`: binary when the size is exactly
//! 84 + 50·n for the count n in the header, else ASCII when the file
//! begins with `solid`, its `vertex` lines read three by three. OFF is
//! Geomview's (CGAL's reader, which OpenSCAD uses): an optional `OFF`
//! header, the counts, the points, then each face as its size and
//! indices, `#` comments. OBJ comes from `tobj` (in f64), 3MF from
//! `threemf` (every mesh object of the model, as OpenSCAD 2021.01's
//! lib3mf import takes them, units not applied), AMF from its XML
//! (`roxmltree`; a zipped AMF through `zip`): every object's mesh, each
//! volume's triangles over the object's vertices, units not applied
//! (OpenSCAD 2021.01's `import_amf.cc`).
//!
//! Identical points are merged (exact equality), so that shared edges are
//! shared by index.

use glam::DVec3;
use std::collections::HashMap;

/// The most triangles (after splitting faces) and points a mesh file may
/// bring.
pub const MAX_POINTS: usize = 1 << 26;

/// A face's point indices: a triangle's three are kept inline, with no
/// allocation of their own (a mesh file may bring millions).
pub type Face = smallvec::SmallVec<[u32; 3]>;

/// Points and faces (index lists, at least 3 each).
#[derive(Debug, Default)]
pub struct MeshFile {
    pub points: Vec<DVec3>,
    pub faces: Vec<Face>,
}

/// What is wrong with a file, and on which of its lines (1-based) when
/// it is text.
#[derive(Debug, PartialEq)]
pub struct FileError {
    pub line: Option<usize>,
    pub message: String,
}

fn err(line: Option<usize>, message: impl Into<String>) -> FileError {
    FileError {
        line,
        message: message.into(),
    }
}

/// The formats by extension (lower case), for messages.
pub const FORMATS: &[&str] = &["stl", "off", "obj", "3mf", "amf", "nef3"];

/// Reads a mesh file of the format its extension `ext` names.
pub fn read(ext: &str, bytes: &[u8]) -> Result<MeshFile, FileError> {
    let mut m = match ext {
        // Merged as read.
        "stl" => return stl(bytes),
        "off" => off(bytes)?,
        "obj" => obj(bytes)?,
        "3mf" => three_mf(bytes)?,
        "amf" => amf(bytes)?,
        "nef3" => super::nef3::read(bytes)?,
        _ => {
            return Err(err(
                None,
                format!("`.{ext}` is not a mesh format csgrt reads"),
            ))
        }
    };
    merge(&mut m);
    Ok(m)
}

/// A fast hasher for coordinate bits (multiply and rotate, as rustc's
/// FxHash): the points of a mesh file are not chosen against it.
#[derive(Default)]
struct Mix(u64);

impl std::hash::Hasher for Mix {
    fn finish(&self) -> u64 {
        // High bits folded down: a coordinate read from f32 has its low
        // 29 bits zero, and the table indexes by the low bits.
        let x = self.0 ^ (self.0 >> 29);
        x.wrapping_mul(0x94_d0_49_bb_13_31_11_eb) ^ (x >> 32)
    }
    fn write(&mut self, bytes: &[u8]) {
        // Eight bytes a word (a point's three coordinates are 24).
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            self.write_u64(u64::from_le_bytes(w.try_into().expect("8 bytes")));
        }
        for b in words.remainder() {
            self.write_u64(*b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    // An array's length, written before its items: one word, not 8 bytes.
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

/// Points merged as they are read (STL lists each corner of each facet):
/// the index of a point with these coordinates, added if new.
struct Merger {
    index: HashMap<[u64; 3], u32, std::hash::BuildHasherDefault<Mix>>,
}

impl Merger {
    fn new(expected: usize) -> Merger {
        Merger {
            index: HashMap::with_capacity_and_hasher(expected, Default::default()),
        }
    }

    fn add(&mut self, m: &mut MeshFile, p: DVec3) -> u32 {
        let key = (p + DVec3::ZERO).to_array().map(f64::to_bits);
        *self.index.entry(key).or_insert_with(|| {
            m.points.push(p);
            m.points.len() as u32 - 1
        })
    }
}

/// Merges points with the same coordinates (bit for bit, −0 as 0).
fn merge(m: &mut MeshFile) {
    let mut merger = Merger::new(m.points.len() / 4);
    let mut kept = MeshFile::default();
    let remap: Vec<u32> = m.points.iter().map(|&p| merger.add(&mut kept, p)).collect();
    for f in &mut m.faces {
        for i in f.iter_mut() {
            *i = remap[*i as usize];
        }
    }
    m.points = kept.points;
}

fn stl(bytes: &[u8]) -> Result<MeshFile, FileError> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if bytes.len() as u64 == 84 + 50 * n as u64 {
            if 3 * n > MAX_POINTS {
                return Err(err(None, format!("more than {MAX_POINTS} points")));
            }
            return finite(binary_stl(&bytes[84..], n));
        }
    }
    if !bytes.starts_with(b"solid") {
        return Err(err(
            None,
            "neither a binary STL (84 + 50·n bytes) nor an ASCII one (beginning with `solid`)",
        ));
    }
    let text = utf8(bytes)?;
    let mut m = MeshFile::default();
    let mut merger = Merger::new(1024);
    let mut corners = [0u32; 3];
    let mut pending = 0;
    for (no, line) in text.lines().enumerate().skip(1) {
        let no = Some(no + 1);
        let line = line.trim();
        let mut words = line.split_whitespace();
        match words.next() {
            Some("outer") => pending = 0,
            Some("vertex") => {
                if pending == 3 {
                    return Err(err(no, "a fourth vertex in one facet"));
                }
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    let w = words
                        .next()
                        .ok_or_else(|| err(no, "expected three numbers after `vertex`"))?;
                    *c = w
                        .parse::<f64>()
                        .map_err(|_| err(no, format!("`{w}` is not a number")))?;
                }
                if m.faces.len() >= MAX_POINTS {
                    return Err(err(no, format!("more than {MAX_POINTS} facets")));
                }
                if !xyz.iter().all(|c| c.is_finite()) {
                    return Err(err(no, "a point is not finite"));
                }
                corners[pending] = merger.add(&mut m, DVec3::from_array(xyz));
                pending += 1;
                if pending == 3 {
                    m.faces.push(Face::from_slice(&corners));
                }
            }
            _ => {}
        }
    }
    finite(m)
}

/// The `n` facets of a binary STL (`body`: 50 bytes each), corners merged
/// as they are read. STL's coordinates are `f32`: they are kept so, and
/// the table that merges them holds indices only (a corner's coordinates
/// are looked up in the points), about 5 bytes a point, so that reading
/// needs little beyond the file itself and the faces.
fn binary_stl(body: &[u8], n: usize) -> MeshFile {
    let mut faces: Vec<Face> = Vec::with_capacity(n);
    // A closed mesh has about half as many points as facets.
    let mut points: Vec<[f32; 3]> = Vec::with_capacity(n / 2 + 16);
    let mut table: hashbrown::HashTable<u32> = hashbrown::HashTable::with_capacity(n / 2 + 16);
    // −0 as 0 (adding +0 does it), then the bits.
    let bits = |p: &[f32; 3]| p.map(|c| (c + 0.0).to_bits());
    let hash = |b: [u32; 3]| {
        use std::hash::Hasher;
        let mut h = Mix::default();
        h.write_u64(u64::from(b[0]) | u64::from(b[1]) << 32);
        h.write_u64(u64::from(b[2]));
        h.finish()
    };
    for r in body.chunks_exact(50).take(n) {
        let f = |i: usize| f32::from_le_bytes([r[i], r[i + 1], r[i + 2], r[i + 3]]);
        let mut face = Face::new();
        for v in 0..3 {
            let at = 12 + 12 * v;
            let p = [f(at), f(at + 4), f(at + 8)];
            let key = bits(&p);
            let h = hash(key);
            let id = match table.find(h, |&i| bits(&points[i as usize]) == key) {
                Some(&i) => i,
                None => {
                    let i = points.len() as u32;
                    points.push(p);
                    table.insert_unique(h, i, |&j| hash(bits(&points[j as usize])));
                    i
                }
            };
            face.push(id);
        }
        faces.push(face);
    }
    drop(table);
    let points = points
        .iter()
        .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
        .collect();
    MeshFile { points, faces }
}

/// The file as text, or the line of its first byte that is not UTF-8.
fn utf8(bytes: &[u8]) -> Result<&str, FileError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        err(Some(line), "a byte that is not UTF-8 text")
    })
}

fn finite(m: MeshFile) -> Result<MeshFile, FileError> {
    if m.points.iter().any(|p| !p.is_finite()) {
        return Err(err(None, "a point is not finite"));
    }
    Ok(m)
}

fn off(bytes: &[u8]) -> Result<MeshFile, FileError> {
    let text = utf8(bytes)?;
    // The lines that say something, comments dropped, with their numbers.
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            (
                i + 1,
                l.split('#')
                    .next()
                    .unwrap_or("")
                    .split_whitespace()
                    .collect::<Vec<_>>(),
            )
        })
        .filter(|(_, w)| !w.is_empty());
    let mut last = 1;
    let mut next = |what: &str| {
        let l = lines.next().ok_or_else(|| {
            err(
                Some(last),
                format!("the file ends where {what} was expected"),
            )
        })?;
        last = l.0;
        Ok::<_, FileError>(l)
    };
    let (mut line, mut head) = next("`OFF`")?;
    // CGAL's header, as OpenSCAD reads it: [ST][C][N][4][n]OFF — texture
    // coordinates, colours and normals after a point's coordinates (left
    // unread), a fourth, homogeneous coordinate, and a dimension (3).
    let mut homogeneous = false;
    if let Some(prefix) = head[0].strip_suffix("OFF") {
        let mut rest = prefix;
        for flag in ["ST", "C", "N", "4", "n"] {
            if let Some(r) = rest.strip_prefix(flag) {
                homogeneous |= flag == "4";
                rest = r;
            }
        }
        if !rest.is_empty() {
            return Err(err(
                Some(line),
                format!(
                    "`{}` is not an OFF header: expected [ST][C][N][4][n]OFF",
                    head[0]
                ),
            ));
        }
        let dimension = prefix.ends_with('n');
        head.remove(0);
        if head.is_empty() {
            (line, head) = next("the numbers of points, faces and edges")?;
        }
        if dimension {
            if head[0] != "3" {
                return Err(err(
                    Some(line),
                    format!("an nOFF file of dimension `{}`: expected 3", head[0]),
                ));
            }
            head.remove(0);
            if head.is_empty() {
                (line, head) = next("the numbers of points, faces and edges")?;
            }
        }
    }
    let coordinates = if homogeneous { 4 } else { 3 };
    let count = |line: usize, w: Option<&&str>, what: &str| -> Result<usize, FileError> {
        let w = w.ok_or_else(|| err(Some(line), format!("expected {what}")))?;
        w.parse::<usize>()
            .map_err(|_| err(Some(line), format!("expected {what}, found `{w}`")))
    };
    let nv = count(line, head.first(), "the number of points")?;
    let nf = count(line, head.get(1), "the number of faces")?;
    if nv > MAX_POINTS || nf > MAX_POINTS {
        return Err(err(
            Some(line),
            format!("more than {MAX_POINTS} points or faces"),
        ));
    }
    let mut m = MeshFile::default();
    for _ in 0..nv {
        let (l, w) = next("a point")?;
        if w.len() < coordinates {
            return Err(err(
                Some(l),
                format!("expected a point's {coordinates} coordinates"),
            ));
        }
        let mut xyzw = [1.0; 4];
        for (c, word) in xyzw.iter_mut().zip(&w[..coordinates]) {
            *c = word
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| err(Some(l), format!("expected a coordinate, found `{word}`")))?;
        }
        let [x, y, z, w] = xyzw;
        // The fault: the homogeneous coordinate not divided by.
        let w = if crate::mutant::active("off_w_ignored") {
            1.0
        } else {
            w
        };
        m.points.push(DVec3::new(x, y, z) / w);
    }
    for _ in 0..nf {
        // A face's size and indices; a colour may follow on its line.
        let (l, w) = next("a face")?;
        let k = count(l, w.first(), "the number of a face's points")?;
        if k < 3 {
            return Err(err(
                Some(l),
                format!("a face of {k} points: expected 3 or more"),
            ));
        }
        if w.len() < k + 1 {
            return Err(err(
                Some(l),
                format!("a face of {k} points lists {}", w.len() - 1),
            ));
        }
        let mut f = Vec::with_capacity(k);
        for word in &w[1..=k] {
            let i = count(l, Some(word), "a point index")?;
            if i >= nv {
                return Err(err(
                    Some(l),
                    format!(
                        "point index {i} is out of range: expected 0 to {}",
                        nv.saturating_sub(1)
                    ),
                ));
            }
            f.push(i as u32);
        }
        m.faces.push(Face::from_vec(f));
    }
    Ok(m)
}

fn obj(bytes: &[u8]) -> Result<MeshFile, FileError> {
    let opts = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _) =
        tobj::load_obj_buf(&mut reader, &opts, |_| Err(tobj::LoadError::OpenFileFailed))
            .map_err(|e| err(None, format!("not a readable OBJ file: {e}")))?;
    let mut m = MeshFile::default();
    for model in models {
        let mesh = &model.mesh;
        let base = m.points.len() as u32;
        for p in mesh.positions.chunks_exact(3) {
            m.points.push(DVec3::new(p[0], p[1], p[2]));
        }
        let arities: Vec<u32> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.clone()
        };
        let mut at = 0usize;
        for k in arities {
            let k = k as usize;
            let f: Vec<u32> = mesh.indices[at..at + k].iter().map(|&i| base + i).collect();
            at += k;
            if f.len() >= 3 {
                m.faces.push(Face::from_vec(f));
            }
        }
        if m.points.len() > MAX_POINTS {
            return Err(err(None, format!("more than {MAX_POINTS} points")));
        }
    }
    finite(m)
}

fn three_mf(bytes: &[u8]) -> Result<MeshFile, FileError> {
    let models = threemf::read(std::io::Cursor::new(bytes))
        .map_err(|e| err(None, format!("not a readable 3MF file: {e}")))?;
    let mut m = MeshFile::default();
    for model in models {
        for o in &model.resources.object {
            let Some(mesh) = &o.mesh else { continue };
            let base = m.points.len() as u32;
            for v in &mesh.vertices.vertex {
                m.points.push(DVec3::new(v.x, v.y, v.z));
            }
            let n = mesh.vertices.vertex.len();
            for t in &mesh.triangles.triangle {
                let ix = [t.v1, t.v2, t.v3];
                if ix.iter().any(|&i| i >= n) {
                    return Err(err(
                        None,
                        format!(
                            "a triangle's point index is out of range: expected 0 to {}",
                            n.saturating_sub(1)
                        ),
                    ));
                }
                m.faces.push(ix.iter().map(|&i| base + i as u32).collect());
            }
            if m.points.len() > MAX_POINTS {
                return Err(err(None, format!("more than {MAX_POINTS} points")));
            }
        }
    }
    finite(m)
}

/// A height grid for `surface()`: `z[(row, column)]`, missing entries 0
/// (OpenSCAD's map default), and its size.
#[derive(Debug, Default, PartialEq)]
pub struct Heights {
    pub rows: usize,
    pub columns: usize,
    pub z: HashMap<(usize, usize), f64>,
}

/// The most grid points a surface may have.
pub const MAX_HEIGHTS: usize = 1 << 24;

/// `surface()`'s heights, as OpenSCAD 2021.01's `surface.cc` reads them:
/// a PNG (by its signature) gives row `height − 1 − y`, column x the
/// value 100/255 · p (or 100/255 · (1 − p) when `invert`, OpenSCAD's own
/// formula) for the pixel's p = 0.2126 r + 0.7152 g + 0.0722 b; anything
/// else is a `.dat` text grid: lines (blank ones and those starting with
/// `#` skipped) of numbers separated by spaces or tabs, reading stopping,
/// with a warning, at the first word that is not a number.
pub fn heights(bytes: &[u8], invert: bool) -> Result<(Heights, Option<FileError>), FileError> {
    let mut h = Heights::default();
    if bytes.starts_with(&[0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]) {
        let img = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
            .map_err(|e| err(None, format!("not a readable PNG image: {e}")))?
            .to_rgba8();
        let (w, ht) = img.dimensions();
        if w as usize * ht as usize > MAX_HEIGHTS {
            return Err(err(None, format!("more than {MAX_HEIGHTS} pixels")));
        }
        for (x, y, p) in img.enumerate_pixels() {
            let [r, g, b, _] = p.0;
            let pixel = 0.2126 * r as f64 + 0.7152 * g as f64 + 0.0722 * b as f64;
            let z = 100.0 / 255.0 * if invert { 1.0 - pixel } else { pixel };
            h.z.insert(((ht - 1 - y) as usize, x as usize), z);
        }
        h.rows = ht as usize;
        h.columns = w as usize;
        return Ok((h, None));
    }
    let text = String::from_utf8_lossy(bytes);
    let mut warning = None;
    let mut row = 0;
    'lines: for (no, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        for (col, w) in line
            .split([' ', '\t'])
            .filter(|w| !w.is_empty())
            .enumerate()
        {
            match w.parse::<f64>() {
                Ok(v) if v.is_finite() => {
                    if h.z.len() >= MAX_HEIGHTS {
                        return Err(err(
                            Some(no + 1),
                            format!("more than {MAX_HEIGHTS} heights"),
                        ));
                    }
                    h.z.insert((row, col), v);
                    h.columns = h.columns.max(col + 1);
                }
                _ => {
                    warning = Some(err(
                        Some(no + 1),
                        format!("`{w}` is not a number: the heights end here"),
                    ));
                    break 'lines;
                }
            }
        }
        row += 1;
    }
    h.rows = if h.z.is_empty() {
        0
    } else {
        h.z.keys().map(|k| k.0 + 1).max().unwrap_or(0)
    };
    Ok((h, warning))
}

/// OpenSCAD's solid over a height grid (`SurfaceNode::createGeometry`):
/// each cell four triangles to its centre at the mean of its corners,
/// walls down to min(0, lowest − 1) on the four sides, and the bottom —
/// here a fan from its centre, which shares every wall's lower edge (the
/// same plane OpenSCAD fills with one polygon).
pub fn surface_mesh(h: &Heights, center: bool) -> MeshFile {
    let (rows, cols) = (h.rows, h.columns);
    let z = |i: usize, j: usize| h.z.get(&(i, j)).copied().unwrap_or(0.0);
    let low = h.z.values().fold(0.0f64, |m, &v| m.min(v - 1.0));
    let (ox, oy) = if center {
        (-((cols as f64) - 1.0) / 2.0, -((rows as f64) - 1.0) / 2.0)
    } else {
        (0.0, 0.0)
    };
    let mut m = MeshFile::default();
    let point = |m: &mut MeshFile, x: f64, y: f64, zz: f64| {
        m.points.push(DVec3::new(ox + x, oy + y, zz));
        m.points.len() as u32 - 1
    };
    if rows < 2 || cols < 2 {
        return m;
    }
    for i in 1..rows {
        for j in 1..cols {
            let (v1, v2, v3, v4) = (z(i - 1, j - 1), z(i - 1, j), z(i, j - 1), z(i, j));
            let vx = (v1 + v2 + v3 + v4) / 4.0;
            let (x0, x1, y0, y1) = ((j - 1) as f64, j as f64, (i - 1) as f64, i as f64);
            let a = point(&mut m, x0, y0, v1);
            let b = point(&mut m, x1, y0, v2);
            let c = point(&mut m, x0, y1, v3);
            let d = point(&mut m, x1, y1, v4);
            let e = point(&mut m, x0 + 0.5, y0 + 0.5, vx);
            m.faces.extend([
                smallvec::smallvec![a, b, e],
                smallvec::smallvec![b, d, e],
                smallvec::smallvec![d, c, e],
                smallvec::smallvec![c, a, e],
            ]);
        }
    }
    // The rim, counter-clockwise seen from above: (x, y) grid corners.
    let mut rim: Vec<(usize, usize)> = Vec::new();
    rim.extend((0..cols - 1).map(|j| (0, j)));
    rim.extend((0..rows - 1).map(|i| (i, cols - 1)));
    rim.extend((1..cols).rev().map(|j| (rows - 1, j)));
    rim.extend((1..rows).rev().map(|i| (i, 0)));
    let centre = point(
        &mut m,
        (cols as f64 - 1.0) / 2.0,
        (rows as f64 - 1.0) / 2.0,
        low,
    );
    for k in 0..rim.len() {
        let (p, q) = (rim[k], rim[(k + 1) % rim.len()]);
        let pl = point(&mut m, p.1 as f64, p.0 as f64, low);
        let ph = point(&mut m, p.1 as f64, p.0 as f64, z(p.0, p.1));
        let ql = point(&mut m, q.1 as f64, q.0 as f64, low);
        let qh = point(&mut m, q.1 as f64, q.0 as f64, z(q.0, q.1));
        m.faces.push(smallvec::smallvec![pl, ql, qh, ph]);
        m.faces.push(smallvec::smallvec![centre, ql, pl]);
    }
    merge(&mut m);
    m
}

/// The most bytes an AMF's XML may unzip to.
pub const MAX_AMF_BYTES: u64 = 1 << 30;

fn amf(bytes: &[u8]) -> Result<MeshFile, FileError> {
    let unzipped;
    let xml: &[u8] = if bytes.starts_with(b"PK") {
        let mut z = zip::ZipArchive::new(std::io::Cursor::new(bytes))
            .map_err(|e| err(None, format!("not a readable zipped AMF: {e}")))?;
        let mut f = z
            .by_index(0)
            .map_err(|e| err(None, format!("not a readable zipped AMF: {e}")))?;
        let mut v = Vec::new();
        use std::io::Read;
        (&mut f)
            .take(MAX_AMF_BYTES)
            .read_to_end(&mut v)
            .map_err(|e| err(None, format!("not a readable zipped AMF: {e}")))?;
        unzipped = v;
        &unzipped
    } else {
        bytes
    };
    let text = utf8(xml)?;
    let doc = roxmltree::Document::parse(text)
        .map_err(|e| err(Some(e.pos().row as usize), format!("not AMF's XML: {e}")))?;
    let line = |n: roxmltree::Node| Some(doc.text_pos_at(n.range().start).row as usize);
    fn child<'a, 'i>(n: roxmltree::Node<'a, 'i>, name: &str) -> Option<roxmltree::Node<'a, 'i>> {
        n.children().find(|c| c.has_tag_name(name))
    }
    let number = |n: roxmltree::Node, name: &str| -> Result<f64, FileError> {
        let c = child(n, name).ok_or_else(|| err(line(n), format!("expected <{name}>")))?;
        let t = c.text().unwrap_or("").trim();
        t.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| err(line(c), format!("<{name}> holds `{t}`, not a number")))
    };
    let mut m = MeshFile::default();
    let root = doc.root_element();
    if !root.has_tag_name("amf") {
        return Err(err(line(root), "expected an <amf> document"));
    }
    for mesh in root
        .children()
        .filter(|o| o.has_tag_name("object"))
        .filter_map(|o| child(o, "mesh"))
    {
        let base = m.points.len() as u32;
        let mut count = 0u32;
        if let Some(vs) = child(mesh, "vertices") {
            for v in vs.children().filter(|v| v.has_tag_name("vertex")) {
                let c = child(v, "coordinates")
                    .ok_or_else(|| err(line(v), "expected <coordinates>"))?;
                m.points.push(DVec3::new(
                    number(c, "x")?,
                    number(c, "y")?,
                    number(c, "z")?,
                ));
                count += 1;
                if m.points.len() > MAX_POINTS {
                    return Err(err(line(v), format!("more than {MAX_POINTS} points")));
                }
            }
        }
        for vol in mesh.children().filter(|v| v.has_tag_name("volume")) {
            for t in vol.children().filter(|t| t.has_tag_name("triangle")) {
                let mut f = Vec::with_capacity(3);
                for k in ["v1", "v2", "v3"] {
                    let i = number(t, k)?;
                    if i.fract() != 0.0 || i < 0.0 || i >= count as f64 {
                        return Err(err(
                            line(t),
                            format!(
                                "<{k}> {i} is out of range: expected 0 to {}",
                                count.saturating_sub(1)
                            ),
                        ));
                    }
                    f.push(base + i as u32);
                }
                m.faces.push(Face::from_vec(f));
            }
        }
    }
    Ok(m)
}

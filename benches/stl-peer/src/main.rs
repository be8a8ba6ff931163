//! Reads one STL file with Chamfer's loader and with stl_io 0.11, round after round, and prints
//! the median seconds of each as JSON:
//!
//! - `chamfer_load`: `load::load` (read the file, parse, check): the soup, one vertex per corner;
//! - `chamfer_load_weld`: the same plus the bake's default weld, an indexed mesh;
//! - `stl_io_soup`: `stl_io::create_stl_reader` collected into triangles (parse only);
//! - `stl_io_indexed`: `stl_io::read_stl`, which indexes vertices (stl_io's weld: exact positions);
//! - `read_file`, `chamfer_parse_in_memory`: `chamfer_load` in its two halves.

use std::io::BufReader;
use std::path::Path;
use std::time::Instant;

use chamfer_preprocess::weld::weld;
use chamfer_preprocess::{Limits, WeldTolerance, load};

fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let file = args.first().ok_or("usage: chamfer-stl-peer FILE.stl [ROUNDS]")?;
    let rounds: usize = args.get(1).map_or(Ok(5), |r| r.parse())?;
    let path = Path::new(file);
    let mut times: [Vec<f64>; 6] = Default::default();
    let mut counts = (0, 0, 0, 0);
    for _ in 0..rounds.max(1) {
        let start = Instant::now();
        std::hint::black_box(load::load(path, &Limits::DEFAULT)?);
        times[0].push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let mesh = load::load(path, &Limits::DEFAULT)?.mesh;
        let distance = WeldTolerance::DEFAULT.distance(&mesh.positions);
        let welded = weld(&mesh.positions, distance);
        times[1].push(start.elapsed().as_secs_f64());
        counts.0 = mesh.triangles.len();
        counts.1 = welded.positions.len();

        let start = Instant::now();
        let mut reader = BufReader::new(std::fs::File::open(path)?);
        let triangles: Vec<stl_io::Triangle> =
            stl_io::create_stl_reader(&mut reader)?.collect::<Result<_, _>>()?;
        times[2].push(start.elapsed().as_secs_f64());
        counts.2 = triangles.len();
        drop(triangles);

        let start = Instant::now();
        let mut reader = BufReader::new(std::fs::File::open(path)?);
        let indexed = stl_io::read_stl(&mut reader)?;
        times[3].push(start.elapsed().as_secs_f64());
        counts.3 = indexed.vertices.len();

        let start = Instant::now();
        let bytes = std::fs::read(path)?;
        times[4].push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        std::hint::black_box(load::load_bytes(path, &bytes, &Limits::DEFAULT)?);
        times[5].push(start.elapsed().as_secs_f64());
    }
    let [a, b, c, d, read, parse] = times.map(median);
    println!(
        "{}",
        serde_json::json!({
            "file": file,
            "rounds": rounds,
            "triangles": counts.0,
            "chamfer_welded_vertices": counts.1,
            "stl_io_triangles": counts.2,
            "stl_io_indexed_vertices": counts.3,
            "chamfer_load": a,
            "chamfer_load_weld": b,
            "stl_io_soup": c,
            "stl_io_indexed": d,
            "read_file": read,
            "chamfer_parse_in_memory": parse,
        })
    );
    Ok(())
}

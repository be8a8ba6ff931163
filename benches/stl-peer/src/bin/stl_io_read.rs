//! What stl_io 0.11 makes of one file (for the hostile and two-solid rows of BENCHMARKS.md "STL and
//! 3MF"): the triangles `read_stl` returns, or its error.
//!
//!     stl_io_read FILE.stl

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let file = std::env::args().nth(1).ok_or("usage: stl_io_read FILE.stl")?;
    let mut reader = std::io::BufReader::new(std::fs::File::open(&file)?);
    match stl_io::read_stl(&mut reader) {
        Ok(mesh) => println!("{file}: {} triangles", mesh.faces.len()),
        Err(e) => println!("{file}: error: {e}"),
    }
    Ok(())
}

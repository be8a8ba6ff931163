//! Writing an asset: header, then each section on a 16-byte boundary. Two sections are derived
//! here rather than held: the edge clusters (when the asset has none) and the render vertex counts
//! that replace the render positions when they can.

use std::io::{self, Write};

use super::{
    Asset, EdgeCluster, FORMAT_VERSION, MAGIC, SECTION_ALIGN, SectionEntry, SectionKind, envelope,
};

const PREAMBLE_BYTES: u64 = 16;

fn align(offset: u64) -> u64 {
    offset.next_multiple_of(SECTION_ALIGN as u64)
}

impl Asset {
    /// Writes the asset to `out`; the header's section table is computed here, whatever it held.
    ///
    /// The output depends only on the asset's contents, so equal assets encode to equal bytes.
    /// Fails only if `out` fails (or, impossibly for real assets, if the header exceeds 1 MiB).
    pub fn encode(&self, out: &mut impl Write) -> io::Result<()> {
        self.encode_as(FORMAT_VERSION, &SectionKind::ALL, &self.clusters(), out)
    }

    /// Writes the asset as a compact file (format 5, see [`compact`](super::compact)): coded
    /// sections where they apply, raw ones elsewhere.
    ///
    /// With [`CompactOptions::LOSSLESS`](super::CompactOptions::LOSSLESS) the file decodes to an asset equal to this one, provided
    /// its triangles start at the corners meshoptimizer's index codec starts them at (the bake's
    /// do; otherwise a triangle may start at another of its corners, its winding kept). Lossy
    /// options move each topology position by at most
    /// [`Grid::error_bound`](super::compact::Grid::error_bound) per axis and each normal by at most
    /// [`octahedral_error_bound`](super::compact::quantize::octahedral_error_bound), and store the
    /// clusters' bounds quantized and widened so that they still hold the decoded edges.
    /// Fails if `out` fails or the options are out of range.
    pub fn encode_compact(
        &self,
        options: &super::CompactOptions,
        codecs: &(dyn super::Codecs + Sync),
        out: &mut impl Write,
    ) -> io::Result<()> {
        let derived = self.compact_derived(options, codecs)?;
        self.write_as(FORMAT_VERSION, &SectionKind::ALL, &derived, out)
    }

    /// The sections [`encode_compact`](Self::encode_compact) writes, with their bytes' total.
    pub fn encode_compact_to_vec(
        &self,
        options: &super::CompactOptions,
        codecs: &(dyn super::Codecs + Sync),
    ) -> io::Result<Vec<u8>> {
        let mut bytes = Vec::new();
        self.encode_compact(options, codecs, &mut bytes)?;
        Ok(bytes)
    }

    fn compact_derived(
        &self,
        options: &super::CompactOptions,
        codecs: &(dyn super::Codecs + Sync),
    ) -> io::Result<Derived<'static>> {
        options.check().map_err(io::Error::other)?;
        let render_counts = render_vertex_counts(self);
        let coded = super::compact::encode(self, options, render_counts.as_deref(), codecs);
        Ok(Derived {
            clusters: &[],
            render_counts,
            keep_positions: false,
            coded,
            rig: envelope::encode_rig(&self.motion.rig)?,
        })
    }

    /// The sections [`encode`](Self::encode) writes: kind, offset and length in the file.
    pub fn encoded_sections(&self) -> Vec<SectionEntry> {
        let clusters = self.clusters();
        Derived::of(self, &SectionKind::ALL, &clusters)
            .and_then(|derived| self.layout(&SectionKind::ALL, &derived))
            .map_or_else(|_| Vec::new(), |(_, sections)| sections)
    }

    /// Writes the asset in an older layout (tests of reading old files); the sections `kinds` lacks
    /// must be empty.
    #[cfg(test)]
    pub(super) fn encode_version(&self, version: u32, out: &mut impl Write) -> io::Result<()> {
        let kinds = SectionKind::of_version(version)
            .ok_or_else(|| io::Error::other(format!("no format version {version}")))?;
        // The clusters are derived: an older file simply lacks them.
        let lacks_rig = !kinds.contains(&SectionKind::Rig) && !self.motion.rig.is_empty();
        if lacks_rig
            || SectionKind::ALL.iter().any(|k| {
                !kinds.contains(k)
                    && *k != SectionKind::EdgeClusters
                    && !self.section_bytes(*k).is_empty()
            })
        {
            return Err(io::Error::other(format!(
                "version {version} cannot hold this asset's sections"
            )));
        }
        self.encode_as(version, kinds, &self.clusters(), out)
    }

    /// Writes the asset with its clusters as stored, even when they do not match the edges (tests
    /// of the decoder's checks).
    #[cfg(test)]
    pub(super) fn encode_as_stored(&self, out: &mut impl Write) -> io::Result<()> {
        self.encode_as(FORMAT_VERSION, &SectionKind::ALL, &self.edge_clusters, out)
    }

    /// Writes the asset with its render positions and their counts both (tests of the decoder's
    /// checks).
    #[cfg(test)]
    pub(super) fn encode_with_positions_and_counts(&self, out: &mut impl Write) -> io::Result<()> {
        let clusters = self.clusters();
        let mut derived = Derived::of(self, &SectionKind::ALL, &clusters)?;
        derived.keep_positions = true;
        self.write_as(FORMAT_VERSION, &SectionKind::ALL, &derived, out)
    }

    /// Writes the asset with `sections` in place of (or beside) what it would write: a coded
    /// section and its raw twin together, say (tests of the decoder's checks).
    #[cfg(test)]
    pub(super) fn encode_with_sections(
        &self,
        sections: Vec<(SectionKind, Vec<u8>)>,
        out: &mut impl Write,
    ) -> io::Result<()> {
        let clusters = self.clusters();
        let mut derived = Derived::of(self, &SectionKind::ALL, &clusters)?;
        derived.coded = sections;
        self.write_as(FORMAT_VERSION, &SectionKind::ALL, &derived, out)
    }

    fn encode_as(
        &self,
        version: u32,
        kinds: &[SectionKind],
        clusters: &[EdgeCluster],
        out: &mut impl Write,
    ) -> io::Result<()> {
        self.write_as(version, kinds, &Derived::of(self, kinds, clusters)?, out)
    }

    fn write_as(
        &self,
        version: u32,
        kinds: &[SectionKind],
        derived: &Derived<'_>,
        out: &mut impl Write,
    ) -> io::Result<()> {
        let (header_bytes, sections) = self.layout(kinds, derived)?;
        out.write_all(&MAGIC)?;
        out.write_all(&version.to_le_bytes())?;
        out.write_all(&(header_bytes.len() as u32).to_le_bytes())?;
        out.write_all(&header_bytes)?;
        let mut written = PREAMBLE_BYTES + header_bytes.len() as u64;
        for entry in &sections {
            write_zeros(out, entry.offset - written)?;
            let kind = SectionKind::from_u32(entry.kind).expect("layout lists only known kinds");
            out.write_all(self.encoded_section(kind, derived))?;
            written = entry.offset + entry.length;
        }
        Ok(())
    }

    /// The encoded asset in a new vector.
    pub fn encode_to_vec(&self) -> Vec<u8> {
        // The clusters, the derived sections and the layout once, for the capacity and the bytes.
        let clusters = self.clusters();
        let written = Derived::of(self, &SectionKind::ALL, &clusters).and_then(|derived| {
            let capacity = self
                .layout(&SectionKind::ALL, &derived)?
                .1
                .last()
                .map_or(0, |s| s.offset + s.length);
            let mut bytes = Vec::with_capacity(capacity as usize);
            self.write_as(FORMAT_VERSION, &SectionKind::ALL, &derived, &mut bytes)?;
            Ok(bytes)
        });
        // Writing to a Vec cannot fail; the header and rig limits are far above any real asset's.
        written.unwrap_or_else(|e| {
            panic!("chamfer: encoding into memory failed ({e}); please report this")
        })
    }

    /// The size of the encoded asset in bytes.
    pub fn encoded_len(&self) -> u64 {
        self.encoded_sections()
            .last()
            .map_or(0, |s| s.offset + s.length)
    }

    /// A section's bytes as written: the stored ones, or the derived ones.
    fn encoded_section<'a>(&'a self, kind: SectionKind, derived: &'a Derived<'a>) -> &'a [u8] {
        if let Some((_, bytes)) = derived.coded.iter().find(|(k, _)| *k == kind) {
            return bytes;
        }
        // A raw section gives way to its coded twin.
        if kind
            .twin()
            .is_some_and(|twin| derived.coded.iter().any(|(k, _)| *k == twin))
        {
            return &[];
        }
        match kind {
            SectionKind::EdgeClusters => bytemuck::cast_slice(derived.clusters),
            SectionKind::RenderVertexCounts => derived.render_counts.as_deref().unwrap_or(&[]),
            SectionKind::Rig => &derived.rig,
            SectionKind::RenderPositions
                if derived.render_counts.is_some() && !derived.keep_positions =>
            {
                &[]
            }
            _ => self.section_bytes(kind),
        }
    }

    /// The section table and the header bytes that describe it.
    fn layout(
        &self,
        kinds: &[SectionKind],
        derived: &Derived<'_>,
    ) -> io::Result<(Vec<u8>, Vec<SectionEntry>)> {
        let mut header = self.header.clone();
        header.sections = kinds
            .iter()
            .map(|&kind| SectionEntry {
                kind: kind as u32,
                offset: 0,
                length: self.encoded_section(kind, derived).len() as u64,
            })
            .collect();
        // The header's size does not depend on the offsets (fixed-width integers), so measure it
        // first, then place the sections after it.
        let header_len = envelope::encode_header(&header)?.len() as u64;
        let mut offset = PREAMBLE_BYTES + header_len;
        for entry in &mut header.sections {
            entry.offset = align(offset);
            offset = entry.offset + entry.length;
        }
        let bytes = envelope::encode_header(&header)?;
        debug_assert_eq!(bytes.len() as u64, header_len);
        Ok((bytes, header.sections))
    }
}

fn write_zeros(out: &mut impl Write, count: u64) -> io::Result<()> {
    const ZEROS: [u8; SECTION_ALIGN] = [0; SECTION_ALIGN];
    out.write_all(&ZEROS[..count as usize])
}

/// What `encode` writes without holding it.
struct Derived<'a> {
    clusters: &'a [EdgeCluster],
    /// The render vertex counts, when `kinds` has them and they reproduce the render positions.
    render_counts: Option<Vec<u8>>,
    /// Write the render positions even with the counts (only tests make such a file).
    keep_positions: bool,
    /// The coded sections of a compact file, each in place of its raw twin.
    coded: Vec<(SectionKind, Vec<u8>)>,
    /// The rig section, encoded (empty for a still asset).
    rig: Vec<u8>,
}

impl<'a> Derived<'a> {
    fn of(asset: &Asset, kinds: &[SectionKind], clusters: &'a [EdgeCluster]) -> io::Result<Self> {
        let render_counts = kinds
            .contains(&SectionKind::RenderVertexCounts)
            .then(|| render_vertex_counts(asset))
            .flatten();
        let rig = if kinds.contains(&SectionKind::Rig) {
            envelope::encode_rig(&asset.motion.rig)?
        } else {
            Vec::new()
        };
        Ok(Self {
            clusters,
            render_counts,
            keep_positions: false,
            coded: Vec::new(),
            rig,
        })
    }
}

/// How many render vertices repeat each topology vertex's position, in order, if that reproduces
/// every render position bit for bit with at most 255 per vertex; `None` otherwise, and for an
/// asset without topology vertices (nothing to save).
///
/// Greedy matching is enough: if a render position could belong to this vertex or to a later one
/// with the same position, giving it to this one leaves the same positions for the rest.
fn render_vertex_counts(asset: &Asset) -> Option<Vec<u8>> {
    let render = &asset.render_positions;
    let mut counts = Vec::with_capacity(asset.topology_positions.len());
    let mut next = 0;
    for p in &asset.topology_positions {
        let bits = p.map(f32::to_bits);
        let start = next;
        while next < render.len() && next - start < usize::from(u8::MAX) {
            if render[next].map(f32::to_bits) != bits {
                break;
            }
            next += 1;
        }
        counts.push((next - start) as u8);
    }
    (next == render.len() && !counts.is_empty()).then_some(counts)
}

//! Writing an asset: header, then each section on a 16-byte boundary.

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

    /// Writes the asset in an older layout (tests of reading old files); the sections `kinds` lacks
    /// must be empty.
    #[cfg(test)]
    pub(super) fn encode_version(&self, version: u32, out: &mut impl Write) -> io::Result<()> {
        let kinds = SectionKind::of_version(version)
            .ok_or_else(|| io::Error::other(format!("no format version {version}")))?;
        // The clusters are derived: an older file simply lacks them.
        if SectionKind::ALL.iter().any(|k| {
            !kinds.contains(k)
                && *k != SectionKind::EdgeClusters
                && !self.section_bytes(*k).is_empty()
        }) {
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

    fn encode_as(
        &self,
        version: u32,
        kinds: &[SectionKind],
        clusters: &[EdgeCluster],
        out: &mut impl Write,
    ) -> io::Result<()> {
        let (header_bytes, sections) = self.layout(kinds, clusters)?;
        out.write_all(&MAGIC)?;
        out.write_all(&version.to_le_bytes())?;
        out.write_all(&(header_bytes.len() as u32).to_le_bytes())?;
        out.write_all(&header_bytes)?;
        let mut written = PREAMBLE_BYTES + header_bytes.len() as u64;
        for entry in &sections {
            write_zeros(out, entry.offset - written)?;
            let kind = SectionKind::from_u32(entry.kind).expect("layout lists only known kinds");
            out.write_all(self.encoded_section(kind, clusters))?;
            written = entry.offset + entry.length;
        }
        Ok(())
    }

    /// The encoded asset in a new vector.
    pub fn encode_to_vec(&self) -> Vec<u8> {
        let mut bytes = Vec::with_capacity(self.encoded_len() as usize);
        // Writing to a Vec cannot fail; the header limit is far above any real header.
        if let Err(e) = self.encode(&mut bytes) {
            panic!("chamfer: encoding into memory failed ({e}); please report this");
        }
        bytes
    }

    /// The size of the encoded asset in bytes.
    pub fn encoded_len(&self) -> u64 {
        match self.layout(&SectionKind::ALL, &self.clusters()) {
            Ok((_, sections)) => sections.last().map_or(0, |s| s.offset + s.length),
            Err(_) => 0,
        }
    }

    /// A section's bytes as written: the stored ones, or `clusters` for the clusters.
    fn encoded_section<'a>(&'a self, kind: SectionKind, clusters: &'a [EdgeCluster]) -> &'a [u8] {
        match kind {
            SectionKind::EdgeClusters => bytemuck::cast_slice(clusters),
            _ => self.section_bytes(kind),
        }
    }

    /// The section table and the header bytes that describe it.
    fn layout(
        &self,
        kinds: &[SectionKind],
        clusters: &[EdgeCluster],
    ) -> io::Result<(Vec<u8>, Vec<SectionEntry>)> {
        let mut header = self.header.clone();
        header.sections = kinds
            .iter()
            .map(|&kind| SectionEntry {
                kind: kind as u32,
                offset: 0,
                length: self.encoded_section(kind, clusters).len() as u64,
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

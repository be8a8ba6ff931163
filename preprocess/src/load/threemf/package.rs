//! The 3MF container: an OPC package (a zip) whose root relationships (`_rels/.rels`) name the 3D
//! model part (3MF core specification §2, "Package"). Parts are inflated as capped streams: no part
//! may inflate past [`Limits::max_input_bytes`], whatever its zip header declares (a zip bomb ends
//! at the limit, not in memory).

use std::io::{Cursor, Read};
use std::path::Path;

use quick_xml::events::Event;

use super::invalid;
use crate::limits::Limited;
use crate::load::files::read_capped;
use crate::{Error, Limits};

/// The relationship type of the 3D model part.
const MODEL_RELATIONSHIP: &str = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";
/// Where writers put the model part; read when the package has no root relationships.
const CONVENTIONAL_MODEL: &str = "3D/3dmodel.model";
/// The most bytes a part's declared size may reserve up front (the read grows past it if true).
const RESERVE_CAP: u64 = 1 << 26;

/// An opened 3MF package.
pub(super) struct Package<'a> {
    path: &'a Path,
    archive: zip::ZipArchive<Cursor<&'a [u8]>>,
    limits: &'a Limits,
}

impl<'a> Package<'a> {
    pub(super) fn open(path: &'a Path, bytes: &'a [u8], limits: &'a Limits) -> Result<Self, Error> {
        let archive = zip::ZipArchive::new(Cursor::new(bytes))
            .map_err(|e| invalid(path, format!("not a zip package: {e}")))?;
        Ok(Self {
            path,
            archive,
            limits,
        })
    }

    /// The part named `name` (no leading `/`), inflated, or `None` if the package has none.
    fn part(&mut self, name: &str) -> Result<Option<Vec<u8>>, Error> {
        let path = self.path;
        let limit = self.limits.max_input_bytes;
        let mut entry = match self.archive.by_name(name) {
            Ok(entry) => entry,
            Err(zip::result::ZipError::FileNotFound) => return Ok(None),
            Err(e) => return Err(invalid(path, format!("part {name}: {e}"))),
        };
        let declared = entry.size();
        let bytes = read_capped(
            &mut entry as &mut dyn Read,
            declared.min(RESERVE_CAP),
            limit,
        )
        .map_err(|e| invalid(path, format!("part {name}: {e}")))?;
        match bytes {
            Some(bytes) => Ok(Some(bytes)),
            None => Err(Error::LimitExceeded {
                path: path.to_owned(),
                what: Limited::InputBytes,
                count: limit.saturating_add(1),
                limit,
            }),
        }
    }

    /// The 3D model part's name and bytes: the target of the root relationship of the 3D model
    /// type, or [`CONVENTIONAL_MODEL`] (with a warning) when the package has no `_rels/.rels`.
    pub(super) fn model(&mut self, warnings: &mut Vec<String>) -> Result<(String, Vec<u8>), Error> {
        let name = match self.part("_rels/.rels")? {
            Some(rels) => {
                model_target(&rels).map_err(|e| invalid(self.path, format!("_rels/.rels: {e}")))?
            }
            None => {
                warnings.push(format!(
                    "the package has no _rels/.rels; reading {CONVENTIONAL_MODEL}"
                ));
                CONVENTIONAL_MODEL.to_owned()
            }
        };
        match self.part(&name)? {
            Some(bytes) => Ok((name, bytes)),
            None => Err(invalid(
                self.path,
                format!("the model part {name} is not in the package"),
            )),
        }
    }
}

/// The target of the first relationship of the 3D model type, without its leading `/`.
fn model_target(rels: &[u8]) -> Result<String, String> {
    let mut reader = quick_xml::Reader::from_reader(rels);
    loop {
        match reader.read_event() {
            Ok(Event::Start(e) | Event::Empty(e)) if e.local_name().as_ref() == "Relationship" => {
                let attribute = |key: &str| {
                    e.attributes()
                        .flatten()
                        .find(|a| a.key.local_name().as_ref() == key)
                        .map(|a| a.value.into_owned())
                };
                if attribute("Type").as_deref() == Some(MODEL_RELATIONSHIP) {
                    let target =
                        attribute("Target").ok_or("a 3D model relationship without a Target")?;
                    return Ok(target.trim_start_matches('/').to_owned());
                }
            }
            Ok(Event::DocType(_)) => return Err("a DOCTYPE (refused: no entity expansion)".into()),
            Ok(Event::Eof) => return Err("no relationship of the 3D model type".into()),
            Ok(_) => {}
            Err(e) => return Err(format!("at byte {}: {e}", reader.error_position())),
        }
    }
}

//! One entry point for every extrusion: the kind by name, the options a
//! user may give (each kind reads some of them and refuses the rest), and
//! [`extrude_selection`], which extrudes a list of faces one by one or
//! together. The CLI, the server and the Python bindings call this instead
//! of choosing among the per-kind functions themselves.

use std::fmt;
use std::str::FromStr;

use holey_dlfl::{FaceId, Mesh};

use super::{
    DomeParams, DooSabinParams, ExtrudeError, ExtrudeParams, MultiExtrudeParams, RegionDirection,
    double_stellate_face, extrude_face, extrude_face_cubical, extrude_face_dodecahedral,
    extrude_face_dome, extrude_face_doo_sabin, extrude_face_icosahedral, extrude_face_octahedral,
    extrude_faces, stellate_face,
};

/// The kind of a single-face extrusion, named as users write it
/// ([`ExtrudeKind::name`], parsed back by [`FromStr`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ExtrudeKind {
    /// [`extrude_face`]: lift, turn and scale the face, join it by quads.
    #[default]
    Plain,
    /// [`extrude_face_cubical`]: plain, by a multiple of the mean edge.
    Cubical,
    /// [`extrude_face_dodecahedral`]: two rings of pentagons.
    Dodecahedral,
    /// [`extrude_face_icosahedral`]: triangles and pentagon fans.
    Icosahedral,
    /// [`extrude_face_octahedral`]: the face turned half a step, joined
    /// by triangles.
    Octahedral,
    /// [`extrude_face_doo_sabin`]: plain, each ring smoothed by the
    /// Doo–Sabin face mask.
    DooSabin,
    /// [`extrude_face_dome`]: rings of quads closing over the face.
    Dome,
    /// [`stellate_face`]: a cone over the face.
    Stellate,
    /// [`double_stellate_face`]: a cone whose triangles are stellated again.
    DoubleStellate,
}

impl ExtrudeKind {
    /// Every kind, in the order users are shown them.
    pub const ALL: [ExtrudeKind; 9] = [
        ExtrudeKind::Plain,
        ExtrudeKind::Cubical,
        ExtrudeKind::Dodecahedral,
        ExtrudeKind::Icosahedral,
        ExtrudeKind::Octahedral,
        ExtrudeKind::DooSabin,
        ExtrudeKind::Dome,
        ExtrudeKind::Stellate,
        ExtrudeKind::DoubleStellate,
    ];

    /// The name users write: `plain`, `doo-sabin`, `double-stellate`, …
    pub fn name(self) -> &'static str {
        match self {
            ExtrudeKind::Plain => "plain",
            ExtrudeKind::Cubical => "cubical",
            ExtrudeKind::Dodecahedral => "dodecahedral",
            ExtrudeKind::Icosahedral => "icosahedral",
            ExtrudeKind::Octahedral => "octahedral",
            ExtrudeKind::DooSabin => "doo-sabin",
            ExtrudeKind::Dome => "dome",
            ExtrudeKind::Stellate => "stellate",
            ExtrudeKind::DoubleStellate => "double-stellate",
        }
    }

    /// One line on what the kind makes, for help texts.
    pub fn summary(self) -> &'static str {
        match self {
            ExtrudeKind::Plain => {
                "Lift the face along its normal, turn and scale it, join it by quads"
            }
            ExtrudeKind::Cubical => {
                "Plain, by the height times the face's mean edge length (cubes on squares)"
            }
            ExtrudeKind::Dodecahedral => {
                "Two rings of pentagons: a regular dodecahedron on a regular pentagon"
            }
            ExtrudeKind::Icosahedral => {
                "Triangles and pentagon fans: a regular icosahedron on a triangle"
            }
            ExtrudeKind::Octahedral => {
                "The face turned half a step and joined by triangles (an octahedron)"
            }
            ExtrudeKind::DooSabin => "Plain, each new ring smoothed by the Doo–Sabin face mask",
            ExtrudeKind::Dome => "Rings of quads closing over the face, finished by a cone",
            ExtrudeKind::Stellate => "A cone: a vertex over the centroid joined to every corner",
            ExtrudeKind::DoubleStellate => "A cone whose triangles are stellated again",
        }
    }

    /// Whether this kind reads `option` (every other option is refused).
    pub fn reads(self, option: ExtrudeOption) -> bool {
        use ExtrudeOption::{Count, Distance, Height, Rotation, Scale, Twist};
        match self {
            ExtrudeKind::Plain => matches!(option, Distance | Scale | Rotation | Count),
            ExtrudeKind::DooSabin => matches!(option, Distance | Scale | Twist | Count),
            ExtrudeKind::Cubical | ExtrudeKind::Dome => matches!(option, Height | Count),
            ExtrudeKind::Dodecahedral | ExtrudeKind::Icosahedral | ExtrudeKind::Octahedral => {
                option == Height
            }
            ExtrudeKind::Stellate | ExtrudeKind::DoubleStellate => option == Distance,
        }
    }
}

impl fmt::Display for ExtrudeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is no [`ExtrudeKind`]'s.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownExtrudeKind(pub String);

impl fmt::Display for UnknownExtrudeKind {
    /// `extrusion kind "pyramid" is not known: use plain, …, stellate or
    /// double-stellate`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "extrusion kind {:?} is not known: use ", self.0)?;
        let last = ExtrudeKind::ALL.len() - 1;
        for (i, kind) in ExtrudeKind::ALL.iter().enumerate() {
            let sep = match i {
                0 => "",
                i if i == last => " or ",
                _ => ", ",
            };
            write!(f, "{sep}{kind}")?;
        }
        Ok(())
    }
}

impl std::error::Error for UnknownExtrudeKind {}

impl FromStr for ExtrudeKind {
    type Err = UnknownExtrudeKind;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ExtrudeKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownExtrudeKind(s.to_owned()))
    }
}

/// An option of [`ExtrudeOptions`] that a kind may or may not read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExtrudeOption {
    /// [`ExtrudeOptions::distance`].
    Distance,
    /// [`ExtrudeOptions::scale`].
    Scale,
    /// [`ExtrudeOptions::rotation_deg`].
    Rotation,
    /// [`ExtrudeOptions::twist`].
    Twist,
    /// The `height` field of [`ExtrudeOptions`].
    Height,
    /// The `count` field of [`ExtrudeOptions`].
    Count,
}

impl ExtrudeOption {
    /// Every option, in the order they are checked.
    pub const ALL: [ExtrudeOption; 6] = [
        ExtrudeOption::Distance,
        ExtrudeOption::Scale,
        ExtrudeOption::Rotation,
        ExtrudeOption::Twist,
        ExtrudeOption::Height,
        ExtrudeOption::Count,
    ];

    /// The name users write: `distance`, `scale`, `rotation`, `twist`,
    /// `height`, `count`.
    pub fn name(self) -> &'static str {
        match self {
            ExtrudeOption::Distance => "distance",
            ExtrudeOption::Scale => "scale",
            ExtrudeOption::Rotation => "rotation",
            ExtrudeOption::Twist => "twist",
            ExtrudeOption::Height => "height",
            ExtrudeOption::Count => "count",
        }
    }
}

impl fmt::Display for ExtrudeOption {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What a user may ask of an extrusion; `None` takes the kind's default.
/// Each kind reads only some options ([`ExtrudeKind::reads`]); a multi-face
/// extrusion (`together`) reads `distance` and `count`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExtrudeOptions {
    /// How far each repetition moves the face along its normal (plain,
    /// Doo–Sabin, together; default 1), or the apex's lift (stellate,
    /// double stellate; default 0).
    pub distance: Option<f64>,
    /// Size of each new face relative to the one before (plain,
    /// Doo–Sabin; default 1).
    pub scale: Option<f64>,
    /// Turn of each repetition about the normal in degrees (plain;
    /// default 0).
    pub rotation_deg: Option<f64>,
    /// Slide of each corner towards the next, a fraction of the edge
    /// (Doo–Sabin; default 0).
    pub twist: Option<f64>,
    /// Height as a multiple of the face's size (cubical, dome,
    /// dodecahedral, icosahedral, octahedral; default 1).
    pub height: Option<f64>,
    /// Repetitions (plain, Doo–Sabin, cubical, together; default 1), or
    /// rings (dome; default [`DomeParams::default`]'s).
    pub count: Option<usize>,
    /// `Some`: lift the faces together as one region ([`extrude_faces`]),
    /// moving this way; only the plain kind does so.
    pub together: Option<RegionDirection>,
}

impl ExtrudeOptions {
    /// Whether `option` was given.
    pub fn given(&self, option: ExtrudeOption) -> bool {
        match option {
            ExtrudeOption::Distance => self.distance.is_some(),
            ExtrudeOption::Scale => self.scale.is_some(),
            ExtrudeOption::Rotation => self.rotation_deg.is_some(),
            ExtrudeOption::Twist => self.twist.is_some(),
            ExtrudeOption::Height => self.height.is_some(),
            ExtrudeOption::Count => self.count.is_some(),
        }
    }

    /// Refuses what `kind` does not read, before anything is done:
    /// [`ExtrudeError::TogetherNotPlain`] for a kind other than plain with
    /// `together`, then the first option given (in [`ExtrudeOption::ALL`]'s
    /// order) that is not read, as [`ExtrudeError::UnreadTogether`] or
    /// [`ExtrudeError::Unread`]. Values are checked by the extrusion.
    pub fn check(&self, kind: ExtrudeKind) -> Result<(), ExtrudeError> {
        if self.together.is_some() && kind != ExtrudeKind::Plain {
            return Err(ExtrudeError::TogetherNotPlain(kind));
        }
        let unread = ExtrudeOption::ALL.into_iter().find(|&o| {
            self.given(o)
                && match self.together {
                    Some(_) => !matches!(o, ExtrudeOption::Distance | ExtrudeOption::Count),
                    None => !kind.reads(o),
                }
        });
        match (unread, self.together) {
            (None, _) => Ok(()),
            (Some(option), Some(_)) => Err(ExtrudeError::UnreadTogether { option }),
            (Some(option), None) => Err(ExtrudeError::Unread { option, kind }),
        }
    }

    fn distance_or(&self, default: f64) -> f64 {
        self.distance.unwrap_or(default)
    }

    fn height(&self) -> f64 {
        self.height.unwrap_or(1.0)
    }

    fn count(&self) -> usize {
        self.count.unwrap_or(1)
    }

    /// Extrudes one face by `kind` with these options.
    fn extrude_one(
        &self,
        mesh: &mut Mesh,
        face: FaceId,
        kind: ExtrudeKind,
    ) -> Result<FaceId, ExtrudeError> {
        let made = match kind {
            ExtrudeKind::Plain => extrude_face(
                mesh,
                face,
                &ExtrudeParams {
                    distance: self.distance_or(1.0),
                    rotation_deg: self.rotation_deg.unwrap_or(0.0),
                    scale: self.scale.unwrap_or(1.0),
                    count: self.count(),
                },
            ),
            ExtrudeKind::DooSabin => extrude_face_doo_sabin(
                mesh,
                face,
                &DooSabinParams {
                    distance: self.distance_or(1.0),
                    twist: self.twist.unwrap_or(0.0),
                    scale: self.scale.unwrap_or(1.0),
                    count: self.count(),
                },
            ),
            ExtrudeKind::Cubical => extrude_face_cubical(mesh, face, self.height(), self.count()),
            ExtrudeKind::Dome => extrude_face_dome(
                mesh,
                face,
                &DomeParams {
                    height_factor: self.height(),
                    rings: self.count.unwrap_or(DomeParams::default().rings),
                },
            ),
            ExtrudeKind::Dodecahedral => extrude_face_dodecahedral(mesh, face, self.height()),
            ExtrudeKind::Icosahedral => extrude_face_icosahedral(mesh, face, self.height()),
            ExtrudeKind::Octahedral => extrude_face_octahedral(mesh, face, self.height()),
            ExtrudeKind::Stellate => stellate_face(mesh, face, self.distance_or(0.0)),
            ExtrudeKind::DoubleStellate => double_stellate_face(mesh, face, self.distance_or(0.0)),
        }?;
        Ok(made.top)
    }
}

/// Extrudes `faces` by `kind`: each face by itself, in the order given
/// (the numbers are the caller's, resolved before the first), or, with
/// [`ExtrudeOptions::together`], all of them as one region
/// ([`extrude_faces`]). Returns the faces at the far end, one per face
/// given (one per distinct face, together).
///
/// Counts are those of the kind's function (see the module's table),
/// summed over the faces.
///
/// Refused, with the mesh unchanged: options the kind does not read
/// ([`ExtrudeOptions::check`]), no faces ([`ExtrudeError::EmptySelection`]),
/// and whatever the kind's function refuses; one by one, that refusal comes
/// as [`ExtrudeError::Face`] naming the face it was about, and the faces
/// before it are put back as they were.
///
/// ```
/// use holey_dlfl::{DVec3, Mesh};
/// use holey_model::extrude::{ExtrudeError, ExtrudeKind, ExtrudeOptions, extrude_selection};
///
/// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
/// let mut tetra = Mesh::from_polygons(p, [[0u32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
/// let faces: Vec<_> = tetra.faces().take(2).collect();
///
/// // Two triangles stellated one by one: +1 vertex, +3 edges, +2 faces each.
/// let kind: ExtrudeKind = "stellate".parse()?;
/// let options = ExtrudeOptions { distance: Some(0.5), ..ExtrudeOptions::default() };
/// let tops = extrude_selection(&mut tetra, &faces, kind, &options)?;
/// assert_eq!(tops.len(), 2);
/// assert_eq!((tetra.vertex_count(), tetra.edge_count(), tetra.face_count()), (6, 12, 8));
///
/// // A stellation has no scale: refused before anything is done.
/// let scaled = ExtrudeOptions { scale: Some(2.0), ..ExtrudeOptions::default() };
/// let refused = extrude_selection(&mut tetra, &tops, kind, &scaled).unwrap_err();
/// assert!(matches!(refused, ExtrudeError::Unread { .. }));
/// assert_eq!(refused.to_string(), "option 'scale' does not apply to the stellate extrusion");
/// assert_eq!(tetra.face_count(), 8);
///
/// // Unknown names are refused by name.
/// assert!("pyramid".parse::<ExtrudeKind>().is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn extrude_selection(
    mesh: &mut Mesh,
    faces: &[FaceId],
    kind: ExtrudeKind,
    options: &ExtrudeOptions,
) -> Result<Vec<FaceId>, ExtrudeError> {
    options.check(kind)?;
    if faces.is_empty() {
        return Err(ExtrudeError::EmptySelection);
    }
    if let Some(direction) = options.together {
        let params = MultiExtrudeParams {
            distance: options.distance_or(1.0),
            direction,
            count: options.count(),
        };
        return extrude_faces(mesh, faces, &params).map(|made| made.tops);
    }
    // Each face is checked before its own extrusion, after the ones
    // before it were made: keep a copy to put back on a refusal (the copy
    // has the same slots and generations, so every handle stays good).
    let backup = (faces.len() > 1).then(|| mesh.clone());
    let mut tops = Vec::with_capacity(faces.len());
    for &face in faces {
        match options.extrude_one(mesh, face, kind) {
            Ok(top) => tops.push(top),
            Err(cause) => {
                if let Some(b) = backup {
                    *mesh = b;
                }
                return Err(ExtrudeError::Face {
                    face,
                    cause: Box::new(cause),
                });
            }
        }
    }
    Ok(tops)
}

//! Selection queries (TopMod's selection menu): face loops, edge loops
//! and rings, grow, shrink, invert, similar and the checkerboard. They
//! read the model and answer display indices of faces or edges; the
//! document does not change.

use holey_dlfl::{EdgeId, FaceId, Mesh};
use holey_model::select::{
    checkerboard, edge_loop, edge_ring, face_loop, grow_faces, invert_edges, invert_faces,
    shrink_faces, similar_faces,
};
use serde_json::json;

use super::request::SelectRequest;
use super::toolbox::{display_edges, display_faces, edges_of, faces_of, plain_ids};
use super::{Reply, Shared};
use crate::ServeError;
use crate::doc::Document;

/// The queries, as requests name them.
pub(super) const QUERIES: &[&str] = &[
    "face-loop",
    "edge-loop",
    "edge-ring",
    "grow",
    "shrink",
    "invert",
    "similar",
    "checkerboard",
];

/// What a query found.
enum Found {
    Faces(Vec<FaceId>),
    Edges(Vec<EdgeId>),
}

impl Shared {
    /// `select`: a query on the current selection (`faces`, `edges`);
    /// answers `faces` or `edges`, display indices of the document's
    /// `version`.
    pub(super) fn select(&self, doc: &Document, req: &SelectRequest) -> Reply {
        doc.check_version(req.version)?;
        doc.check_no_rind()?;
        let query = req.query.as_str();
        let mesh = doc.model("selection")?;
        let faces = faces_of(doc, req.faces.as_deref())?;
        let edges = edges_of(doc, req.edges.as_deref())?;
        let found = run(mesh, query, &faces, &edges).map_err(|e| match e {
            Why::Bad(m) => ServeError::BadRequest(m),
            Why::Refused(m) => {
                ServeError::Refused(format!("{query}: {}", plain_ids(&m, doc.index())))
            }
        })?;
        let index = doc.index();
        Ok(match found {
            Found::Faces(f) => {
                let shown = display_faces(index, &f);
                json!({"faces": shown, "message": format!("{query}: {} faces", shown.len()),
                       "version": doc.version()})
            }
            Found::Edges(e) => {
                let shown = display_edges(index, &e);
                json!({"edges": shown, "message": format!("{query}: {} edges", shown.len()),
                       "version": doc.version()})
            }
        })
    }
}

enum Why {
    Bad(String),
    Refused(String),
}

fn refused(e: impl ToString) -> Why {
    Why::Refused(e.to_string())
}

/// Appends `more` to `out` without repeats, keeping the order.
fn union<T: Copy + PartialEq>(out: &mut Vec<T>, more: Vec<T>) {
    for x in more {
        if !out.contains(&x) {
            out.push(x);
        }
    }
}

fn run(mesh: &Mesh, query: &str, faces: &[FaceId], edges: &[EdgeId]) -> Result<Found, Why> {
    let need_faces = || {
        if faces.is_empty() {
            Err(Why::Refused("select one or more faces first".into()))
        } else {
            Ok(())
        }
    };
    let need_edges = || {
        if edges.is_empty() {
            Err(Why::Refused("select one or more edges first".into()))
        } else {
            Ok(())
        }
    };
    Ok(match query {
        "face-loop" => {
            // Through the selected edges (each from a quad beside it), or,
            // with faces only, through each face across its first edge.
            let mut out = Vec::new();
            if !edges.is_empty() {
                for &e in edges {
                    let face = quad_beside(mesh, e).map_err(refused)?.ok_or_else(|| {
                        Why::Refused(format!(
                            "no quadrilateral borders edge {e}, so no face loop passes through it"
                        ))
                    })?;
                    union(&mut out, face_loop(mesh, face, e).map_err(refused)?);
                }
            } else {
                need_faces()?;
                for &f in faces {
                    let c = mesh.face_corner(f).map_err(refused)?;
                    let e = mesh
                        .corner_edge(c)
                        .map_err(refused)?
                        .ok_or_else(|| Why::Refused(format!("face {f} has no edge")))?;
                    union(&mut out, face_loop(mesh, f, e).map_err(refused)?);
                }
            }
            Found::Faces(out)
        }
        "edge-loop" | "edge-ring" => {
            need_edges()?;
            let mut out = Vec::new();
            for &e in edges {
                let walk = if query == "edge-loop" {
                    edge_loop(mesh, e)
                } else {
                    edge_ring(mesh, e)
                };
                union(&mut out, walk.map_err(refused)?);
            }
            Found::Edges(out)
        }
        "grow" => {
            need_faces()?;
            Found::Faces(grow_faces(mesh, faces).map_err(refused)?)
        }
        "shrink" => {
            need_faces()?;
            Found::Faces(shrink_faces(mesh, faces).map_err(refused)?)
        }
        // Faces when faces are selected (or nothing: every face), edges
        // when only edges are.
        "invert" if faces.is_empty() && !edges.is_empty() => {
            Found::Edges(invert_edges(mesh, edges))
        }
        "invert" => Found::Faces(invert_faces(mesh, faces).map_err(refused)?),
        "similar" => {
            need_faces()?;
            Found::Faces(similar_faces(mesh, faces).map_err(refused)?)
        }
        "checkerboard" => Found::Faces(checkerboard(mesh).map_err(refused)?.first),
        _ => {
            return Err(Why::Bad(format!(
                "unknown query {query:?} (one of {})",
                QUERIES.join(", ")
            )));
        }
    })
}

/// A quadrilateral (not a hole) beside edge `e`, if there is one.
fn quad_beside(mesh: &Mesh, e: EdgeId) -> Result<Option<FaceId>, holey_dlfl::Error> {
    for c in mesh.edge_corners(e)? {
        let f = mesh.corner_face(c)?;
        if mesh.face_len(f)? == 4 && !mesh.is_hole(f)? {
            return Ok(Some(f));
        }
    }
    Ok(None)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    use crate::doc::primitive_mesh as mesh;

    fn faces(found: Found) -> Vec<FaceId> {
        match found {
            Found::Faces(f) => f,
            Found::Edges(_) => panic!("edges"),
        }
    }

    /// On a torus of m × n quads every face loop is a ring of m or n
    /// quads, every edge loop and ring m or n edges, and the quads are
    /// 2-coloured when m and n are even.
    #[test]
    fn loops_rings_and_colourings_of_a_torus_grid() {
        let (m, n) = (8usize, 6usize);
        let t = mesh(&format!("@torus:{m}:{n}"));
        let all: Vec<FaceId> = t.faces().collect();
        assert_eq!(all.len(), m * n);
        let f = all[0];
        let loop_len = faces(run(&t, "face-loop", &[f], &[]).ok().unwrap()).len();
        assert!(loop_len == m || loop_len == n, "{loop_len}");
        for e in t.edges().take(6) {
            for q in ["edge-loop", "edge-ring"] {
                let Ok(Found::Edges(es)) = run(&t, q, &[], &[e]) else {
                    panic!("{q}")
                };
                assert!(es.len() == m || es.len() == n, "{q}: {}", es.len());
            }
            let through = faces(run(&t, "face-loop", &[], &[e]).ok().unwrap()).len();
            assert!(through == m || through == n, "{through}");
        }
        let board = faces(run(&t, "checkerboard", &[], &[]).ok().unwrap());
        assert_eq!(board.len(), m * n / 2);
        // Grow one quad: its 8 neighbours around the vertices join it.
        assert_eq!(faces(run(&t, "grow", &[f], &[]).ok().unwrap()).len(), 9);
        let grown = faces(run(&t, "grow", &[f], &[]).ok().unwrap());
        assert_eq!(faces(run(&t, "shrink", &grown, &[]).ok().unwrap()), vec![f]);
        assert_eq!(
            faces(run(&t, "invert", &[f], &[]).ok().unwrap()).len(),
            m * n - 1
        );
        assert_eq!(
            faces(run(&t, "similar", &[f], &[]).ok().unwrap()).len(),
            m * n
        );
    }

    #[test]
    fn refusals_say_why() {
        let cube = mesh("@cube");
        let tetra = mesh("@tetrahedron");
        let why = |m: &Mesh, q: &str, f: &[FaceId]| match run(m, q, f, &[]) {
            Err(Why::Refused(s) | Why::Bad(s)) => s,
            Ok(_) => panic!("{q} answered"),
        };
        assert!(why(&cube, "grow", &[]).contains("select"));
        assert!(why(&cube, "edge-loop", &[]).contains("edges"));
        assert!(why(&cube, "checkerboard", &[]).contains("2-coloured"));
        let f = tetra.faces().next().unwrap();
        assert!(why(&tetra, "face-loop", &[f]).contains("not a quadrilateral"));
        assert!(why(&cube, "sideways", &[]).contains("unknown query"));
    }
}

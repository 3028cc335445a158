//! `holey demo`: the main job on built-in defaults. It recreates the kinds
//! of models the thesis shows — Sierpinski polyhedra, Menger sponges,
//! rinds with punched and peeled holes, curved and twisted handles, a cup,
//! and their smoothed versions — and a row of TopMod's toolbox (issue 18:
//! a smoothed wireframe dodecahedron, extruded stellations, a honeycomb
//! sphere) from the built-in primitives only, writes each as `.obj`,
//! `.dlfl` and `.png`, and an `index.html` gallery.

use crate::output::outln;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{DVec3, FaceId, Mesh};
use holey_io::WriteOptions;
use holey_model::extrude::{ExtrudeParams, extrude_face, stellate_face};
use holey_model::handle::{HandleParams, create_handle};
use holey_model::menger::{MengerParams, Thickness, menger};
use holey_model::rind::Rind;
use holey_model::sierpinski::sierpinski;
use holey_model::wireframe::wireframe;
use holey_render::{RenderOptions, View};
use holey_subdiv::{RemeshParams, RemeshScheme, catmull_clark, doo_sabin, remesh};

use crate::cmd::render::write_kernel_picture;
use crate::output::write_kernel;

#[derive(clap::Args)]
#[command(after_help = "\
Builds every model from built-in primitives, writes it as .obj, .dlfl and
.png into the output folder with an index.html gallery, and prints a
table of V/E/F, genus and the time each model took to build.

Examples:
  holey demo
  holey demo --out /tmp/gallery --size 1024x768")]
pub struct Args {
    /// Folder to write the gallery into (created if missing).
    #[arg(long, default_value = "holey-demo")]
    pub out: PathBuf,
    /// Picture size, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600")]
    pub size: String,
}

/// One model of the gallery.
struct Model {
    name: &'static str,
    title: &'static str,
    /// How it was made, for the table and the gallery.
    recipe: &'static str,
    build: fn() -> Result<Mesh>,
    view: View,
    edges: bool,
    smooth: bool,
}

fn primitive(spec: &str) -> Result<Mesh> {
    let soup = holey_shapes::parse_primitive(spec).map_err(|e| anyhow!("{spec}: {e}"))?;
    Ok(to_dlfl(&soup, ImportOptions::default())
        .map_err(|e| anyhow!("{spec}: {e}"))?
        .mesh)
}

fn sierpinski_of(spec: &str, n: usize) -> Result<Mesh> {
    let mut m = primitive(spec)?;
    sierpinski(&mut m, n)?;
    Ok(m)
}

fn menger_of(n: usize, exact: bool) -> Result<Mesh> {
    let mut m = primitive("@cube")?;
    let params = MengerParams {
        iterations: n,
        thickness: Thickness::RatioOfMeanEdge(1.0 / 3.0),
        collapse_angle_deg: 90.0,
        exact,
    };
    menger(&mut m, &params)?;
    Ok(m)
}

/// The key of the candidate face whose centroid scores highest (the first
/// of equals), or `None` when there is no candidate.
fn best_by_centroid<K>(
    mesh: &Mesh,
    candidates: impl Iterator<Item = (K, FaceId)>,
    score: impl Fn(DVec3) -> f64,
) -> Result<Option<K>> {
    let mut best: Option<(f64, K)> = None;
    for (key, f) in candidates {
        let ps = mesh.face_positions(f)?;
        let d = score(ps.iter().copied().sum::<DVec3>() / ps.len() as f64);
        if best.as_ref().is_none_or(|(b, _)| d > *b) {
            best = Some((d, key));
        }
    }
    Ok(best.map(|(_, key)| key))
}

/// The face whose centroid lies furthest along `dir`.
fn face_towards(mesh: &Mesh, dir: DVec3) -> Result<FaceId> {
    let solid = mesh.surface_faces().map(|f| (f, f));
    best_by_centroid(mesh, solid, |c| c.dot(dir))?.ok_or_else(|| anyhow!("the mesh has no face"))
}

/// The face whose centroid lies nearest to `p`.
fn face_nearest(mesh: &Mesh, p: DVec3) -> Result<FaceId> {
    best_by_centroid(mesh, mesh.faces().map(|f| (f, f)), |c| {
        -c.distance_squared(p)
    })?
    .ok_or_else(|| anyhow!("the mesh has no face"))
}

/// The outer face of a rind whose centroid lies furthest along `dir`.
fn outer_towards(rind: &Rind, dir: DVec3) -> Result<usize> {
    let outer = (0..rind.input_face_slots()).filter_map(|i| rind.outer_face(i).map(|f| (i, f)));
    best_by_centroid(rind.mesh(), outer, |c| c.dot(dir))?
        .ok_or_else(|| anyhow!("the rind has no outer face"))
}

fn rind_sphere() -> Result<Mesh> {
    let mut rind = Rind::new(primitive("@sphere:2")?, 0.1)?;
    // Punch a ring of single holes and peel a wide window facing the viewer.
    for d in [
        DVec3::new(0.0, -1.0, 0.3),
        DVec3::new(-1.0, 0.0, 0.3),
        DVec3::new(0.3, 0.4, 1.0),
    ] {
        let i = outer_towards(&rind, d.normalize())?;
        rind.punch_index(i)?;
    }
    let centre = DVec3::new(1.0, -0.6, 0.8).normalize();
    let mut window: Vec<usize> = (0..rind.input_face_slots())
        .filter(|&i| {
            rind.outer_face(i).is_some_and(|f| {
                rind.mesh().face_positions(f).is_ok_and(|ps| {
                    let c = ps.iter().copied().sum::<DVec3>() / ps.len() as f64;
                    c.normalize().dot(centre) > 0.93
                })
            })
        })
        .collect();
    window.sort_unstable();
    rind.peel_indices(&window)?;
    Ok(rind.into_mesh())
}

fn handle_on_torus(twist: usize) -> Result<Mesh> {
    let mut m = primitive("@torus:24:12")?;
    // Two faces on top of the ring, on opposite sides: the handle arches
    // over the hole.
    let a = face_towards(&m, DVec3::new(1.0, 0.05, 1.6))?;
    let b = face_towards(&m, DVec3::new(-1.0, -0.05, 1.6))?;
    let ca = m.face_corner(a)?;
    let cb = m
        .face_corners(b)?
        .nth(twist)
        .ok_or_else(|| anyhow!("no such corner"))?;
    create_handle(&mut m, ca, cb, &HandleParams::new(12, 2.0, 2.0))?;
    Ok(m)
}

fn tunnel_through_cube() -> Result<Mesh> {
    let mut m = primitive("@cube:3")?;
    let a = face_nearest(&m, DVec3::Z)?;
    let b = face_nearest(&m, -DVec3::Z)?;
    let (ca, cb) = (m.face_corner(a)?, m.face_corner(b)?);
    create_handle(&mut m, ca, cb, &HandleParams::new(6, -1.0, -1.0))?;
    Ok(m)
}

fn cup() -> Result<Mesh> {
    // Figure 65: a rind body with its top peeled, and a curved handle.
    let mut rind = Rind::new(primitive("@cylinder:16:4")?, 0.12)?;
    let top = outer_towards(&rind, DVec3::Z)?;
    rind.peel_index(top)?;
    let upper = outer_towards(&rind, DVec3::new(1.0, 0.0, 0.45))?;
    let lower = outer_towards(&rind, DVec3::new(1.0, 0.0, -0.45))?;
    let (fa, fb) = (
        rind.outer_face(upper).ok_or_else(|| anyhow!("no face"))?,
        rind.outer_face(lower).ok_or_else(|| anyhow!("no face"))?,
    );
    let mut m = rind.into_mesh();
    let (ca, cb) = (m.face_corner(fa)?, m.face_corner(fb)?);
    create_handle(&mut m, ca, cb, &HandleParams::new(8, 2.0, 2.0))?;
    Ok(m)
}

/// The union of two primitives by Theorem 5.2 of Bernstein & Wojtan: `b`
/// shifted by `shift` arrives from well outside, as `holey union` moves it.
fn union_of(a: &str, b: &str, shift: DVec3) -> Result<Mesh> {
    let tri = |spec: &str| -> Result<holey_topo::TriMesh> {
        let soup = holey_shapes::parse_primitive(spec).map_err(|e| anyhow!("{spec}: {e}"))?;
        Ok(soup.triangulated())
    };
    let (a, mut b) = (tri(a)?, tri(b)?);
    for p in &mut b.positions {
        *p += shift;
    }
    let (start, end) = holey_topo::solids::synthesize(
        &a,
        &b,
        DVec3::from_array(holey_topo::solids::DEFAULT_DIRECTION).normalize(),
    );
    let out = holey_topo::topology_change(&start, &end, &holey_topo::Options::default())?;
    Ok(to_dlfl(&crate::tri::compact(&out.mesh), ImportOptions::default())?.mesh)
}

/// TopMod's wireframe of the dodecahedron (every edge a tube of square
/// section: genus E − V + 1 = 11), smoothed by Catmull–Clark.
fn wireframe_dodecahedron(levels: usize) -> Result<Mesh> {
    let frame = wireframe(&primitive("@dodecahedron")?, 0.22)?;
    Ok(catmull_clark(&frame, levels)?)
}

/// Every face of `spec` extruded (moved out and shrunk) and its top
/// stellated into a spike.
fn extruded_stellations(spec: &str, distance: f64, scale: f64, spike: f64) -> Result<Mesh> {
    let mut m = primitive(spec)?;
    let faces: Vec<FaceId> = m.faces().collect();
    let params = ExtrudeParams {
        distance,
        scale,
        ..ExtrudeParams::default()
    };
    for f in faces {
        let top = extrude_face(&mut m, f, &params)?.top;
        stellate_face(&mut m, top, spike)?;
    }
    Ok(m)
}

/// A honeycomb on a sphere: the dual of a geodesic sphere (hexagons and
/// twelve pentagons, every vertex of valence 3) remeshed by TopMod's
/// honeycomb scheme, which shrinks every face to a copy and makes every
/// vertex a `2·3`-gon: hexagons everywhere but the twelve pentagons.
fn honeycomb_sphere() -> Result<Mesh> {
    let params = RemeshParams::default();
    let dual = remesh(&primitive("@geodesic:3")?, RemeshScheme::Dual, &params, 1)?;
    Ok(remesh(&dual, RemeshScheme::Honeycomb, &params, 1)?)
}

/// The gallery in the order of the table: the thesis's models, then
/// TopMod's tools, then topology change by motion.
fn models() -> Vec<Model> {
    let mut all = thesis_models();
    all.extend(toolbox_models());
    all.extend(motion_models());
    all
}

/// Sierpinski, Menger, rind, handle, tunnel and cup (thesis chapters IV–VII).
fn thesis_models() -> Vec<Model> {
    let iso = View::Iso;
    let tetra_view = View::Direction(DVec3::new(1.0, 0.25, 0.35));
    vec![
        Model {
            name: "sierpinski-tetrahedron",
            title: "Sierpinski tetrahedron",
            recipe: "@tetrahedron, 3 Sierpinski iterations (ch. VI, fig. 39A)",
            build: || sierpinski_of("@tetrahedron", 3),
            view: tetra_view,
            edges: true,
            smooth: false,
        },
        Model {
            name: "sierpinski-tetrahedron-doo-sabin",
            title: "Smoothed Sierpinski tetrahedron",
            recipe: "3 Sierpinski iterations, then 2 Doo–Sabin levels (fig. 43)",
            build: || Ok(doo_sabin(&sierpinski_of("@tetrahedron", 3)?, 2)?),
            view: tetra_view,
            edges: false,
            smooth: true,
        },
        Model {
            name: "sierpinski-cube",
            title: "Sierpinski cube",
            recipe: "@cube, 2 Sierpinski iterations (fig. 39B)",
            build: || sierpinski_of("@cube", 2),
            view: iso,
            edges: true,
            smooth: false,
        },
        Model {
            name: "sierpinski-cube-doo-sabin",
            title: "Smoothed Sierpinski cube",
            recipe: "3 Sierpinski iterations, then 2 Doo–Sabin levels (fig. 44)",
            build: || Ok(doo_sabin(&sierpinski_of("@cube", 3)?, 2)?),
            view: iso,
            edges: false,
            smooth: true,
        },
        Model {
            name: "menger-1",
            title: "Menger sponge, level 1",
            recipe: "@cube, generalized Menger sponge, D = 1/3 of the mean edge (ch. VII)",
            build: || menger_of(1, false),
            view: iso,
            edges: true,
            smooth: false,
        },
        Model {
            name: "menger-2",
            title: "Menger sponge, level 2",
            recipe: "@cube, 2 levels, D = 1/3 of the mean edge at each level (fig. 62)",
            build: || menger_of(2, false),
            view: iso,
            edges: false,
            smooth: false,
        },
        Model {
            name: "menger-2-catmull-clark",
            title: "Smoothed Menger sponge",
            recipe: "the level-2 sponge, 2 Catmull–Clark levels",
            build: || Ok(catmull_clark(&menger_of(2, false)?, 2)?),
            view: iso,
            edges: false,
            smooth: true,
        },
        Model {
            name: "menger-3-exact",
            title: "True Menger sponge, level 3",
            recipe: "@cube, --exact (the thesis's future-work item 4): genus 1409",
            build: || menger_of(3, true),
            view: iso,
            edges: false,
            smooth: false,
        },
        Model {
            name: "rind-sphere",
            title: "Rind sphere",
            recipe: "@sphere:2, rind 0.1 thick, 3 faces punched and a window peeled (ch. V)",
            build: rind_sphere,
            view: View::Direction(DVec3::new(1.0, -0.6, 0.8)),
            edges: true,
            smooth: false,
        },
        Model {
            name: "rind-sphere-doo-sabin",
            title: "Smoothed rind sphere",
            recipe: "the rind sphere, 2 Doo–Sabin levels (fig. 31)",
            build: || Ok(doo_sabin(&rind_sphere()?, 2)?),
            view: View::Direction(DVec3::new(1.0, -0.6, 0.8)),
            edges: false,
            smooth: true,
        },
        Model {
            name: "handle-torus",
            title: "Curved handle",
            recipe: "@torus, a 10-segment handle, w1 = w2 = 2.5 (ch. IV)",
            build: || handle_on_torus(0),
            view: iso,
            edges: true,
            smooth: false,
        },
        Model {
            name: "handle-torus-twisted",
            title: "Twisted handle",
            recipe: "the same faces, other corners matched: the handle twists (fig. 20)",
            build: || handle_on_torus(2),
            view: iso,
            edges: true,
            smooth: false,
        },
        Model {
            name: "tunnel-cube",
            title: "Tunnel",
            recipe: "@cube:3, a 6-segment handle with negative weights: a hole (§IV.2)",
            build: tunnel_through_cube,
            view: View::Direction(DVec3::new(0.25, -0.2, 1.0)),
            edges: true,
            smooth: false,
        },
        Model {
            name: "cup",
            title: "Cup",
            recipe: "@cylinder:16:4 rind with its top peeled, plus a curved handle (fig. 65)",
            build: cup,
            view: View::Direction(DVec3::new(0.3, -1.0, 0.6)),
            edges: true,
            smooth: false,
        },
        Model {
            name: "cup-catmull-clark",
            title: "Smoothed cup",
            recipe: "the cup, 2 Catmull–Clark levels",
            build: || Ok(catmull_clark(&cup()?, 2)?),
            view: View::Direction(DVec3::new(0.3, -1.0, 0.6)),
            edges: false,
            smooth: true,
        },
    ]
}

/// Wireframe, extrusion and remeshing (TopMod's tools, issue 18).
fn toolbox_models() -> Vec<Model> {
    let iso = View::Iso;
    vec![
        Model {
            name: "wireframe-dodecahedron",
            title: "Wireframe dodecahedron",
            recipe: "@dodecahedron, TopMod's wireframe 0.22 thick: every edge a tube, genus E − V + 1 = 11",
            build: || wireframe_dodecahedron(0),
            view: iso,
            edges: true,
            smooth: false,
        },
        Model {
            name: "wireframe-dodecahedron-smoothed",
            title: "Smoothed wireframe dodecahedron",
            recipe: "the wireframe dodecahedron, 2 Catmull–Clark levels",
            build: || wireframe_dodecahedron(2),
            view: iso,
            edges: false,
            smooth: true,
        },
        Model {
            name: "extruded-stellations",
            title: "Extruded stellations",
            recipe: "@dodecahedron, every face extruded 0.3 (scaled 0.55) and its top stellated 1.1 high",
            build: || extruded_stellations("@dodecahedron", 0.3, 0.55, 1.1),
            view: iso,
            edges: true,
            smooth: false,
        },
        Model {
            name: "extruded-stellations-smoothed",
            title: "Smoothed extruded stellations",
            recipe: "@icosahedron, every face extruded 0.6 (scaled 0.45) and its top stellated 0.8 high, then 2 Catmull–Clark levels",
            build: || {
                Ok(catmull_clark(
                    &extruded_stellations("@icosahedron", 0.6, 0.45, 0.8)?,
                    2,
                )?)
            },
            view: iso,
            edges: false,
            smooth: true,
        },
        Model {
            name: "honeycomb-sphere",
            title: "Honeycomb sphere",
            recipe: "@geodesic:3, its dual (hexagons and 12 pentagons), then TopMod's honeycomb remeshing",
            build: honeycomb_sphere,
            view: iso,
            edges: true,
            smooth: false,
        },
    ]
}

/// Unions by moving one solid into another (Bernstein & Wojtan, Theorem 5.2).
fn motion_models() -> Vec<Model> {
    vec![
        Model {
            name: "union-two-tori",
            title: "Two tori moved into each other",
            recipe: "@torus:48:24 and a copy shifted by (1, 0.1, 0.03), which slides in from afar: the topology change of Bernstein & Wojtan deletes what ends inside (Theorem 5.2), leaving genus 1 + 1 + 1",
            build: || union_of("@torus:48:24", "@torus:48:24", DVec3::new(1.0, 0.1, 0.03)),
            view: View::Direction(DVec3::new(0.2, -0.6, 1.0)),
            edges: false,
            smooth: false,
        },
        Model {
            name: "union-torus-sphere",
            title: "A torus swallowing a sphere",
            recipe: "@torus:48:24 and @sphere:4 of radius 1 centred on its tube, united by moving the sphere in (Theorem 5.2)",
            build: || union_of("@torus:48:24", "@sphere:4", DVec3::new(1.0, 0.0, 0.3)),
            view: View::Direction(DVec3::new(0.3, -1.0, 0.8)),
            edges: false,
            smooth: false,
        },
    ]
}

/// A row of the table and the gallery.
struct Row {
    name: &'static str,
    title: &'static str,
    recipe: &'static str,
    v: usize,
    e: usize,
    f: usize,
    genus: i64,
    seconds: f64,
}

pub fn run(args: Args) -> Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let total = Instant::now();
    let mut rows = Vec::new();
    for model in models() {
        let start = Instant::now();
        let mesh = (model.build)().with_context(|| format!("building {}", model.name))?;
        let seconds = start.elapsed().as_secs_f64();
        mesh.validate()
            .with_context(|| format!("{} is not a valid DLFL", model.name))?;
        let opts = RenderOptions {
            view: model.view,
            edges: model.edges,
            smooth: model.smooth,
            ..crate::cmd::render::options(&args.size, "iso", "z", false, false)?
        };
        write_model(&args.out, model.name, &mesh, &opts)?;
        rows.push(Row {
            name: model.name,
            title: model.title,
            recipe: model.recipe,
            v: mesh.vertex_count(),
            e: mesh.edge_count(),
            f: mesh.face_count() - mesh.hole_count(),
            genus: mesh.genus(),
            seconds,
        });
    }
    outln!(
        "{:<34} {:>7} {:>7} {:>7} {:>6} {:>9}",
        "model",
        "V",
        "E",
        "F",
        "genus",
        "build ms"
    )?;
    for r in &rows {
        outln!(
            "{:<34} {:>7} {:>7} {:>7} {:>6} {:>9.1}",
            r.name,
            r.v,
            r.e,
            r.f,
            r.genus,
            r.seconds * 1e3
        )?;
    }
    let index = args.out.join("index.html");
    holey_io::write_bytes_atomic(&index, gallery_html(&rows).as_bytes())
        .map_err(crate::error::from_io)?;
    eprintln!(
        "wrote {} models (.obj, .dlfl, .png) and {} in {:.1} s",
        rows.len(),
        index.display(),
        total.elapsed().as_secs_f64()
    );
    Ok(())
}

fn write_model(dir: &Path, name: &str, mesh: &Mesh, opts: &RenderOptions) -> Result<()> {
    let path = |ext: &str| -> Result<String> {
        dir.join(format!("{name}.{ext}"))
            .to_str()
            .map(str::to_owned)
            .context("output path is not UTF-8")
    };
    write_kernel(&path("obj")?, mesh, &WriteOptions::default())?;
    write_kernel(&path("dlfl")?, mesh, &WriteOptions::default())?;
    write_kernel_picture(&path("png")?, mesh, opts)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn gallery_html(rows: &[Row]) -> String {
    let mut h = String::new();
    h += "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>holey demo</title>\n<style>\n\
          body{font-family:system-ui,sans-serif;margin:2em;background:#f4f5f7;color:#222}\n\
          h1{font-weight:600}.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(340px,1fr));gap:1.2em}\n\
          figure{margin:0;background:#fff;border-radius:8px;box-shadow:0 1px 3px #0002;overflow:hidden}\n\
          figure img{width:100%;display:block}figcaption{padding:.6em .9em;font-size:.9em}\n\
          figcaption b{display:block;font-size:1.05em}.n{color:#555;font-variant-numeric:tabular-nums}\n\
          table{border-collapse:collapse;margin:1.5em 0;background:#fff}td,th{padding:.3em .8em;border-bottom:1px solid #ddd;text-align:right}\n\
          td:first-child,th:first-child{text-align:left}\n</style></head><body>\n\
          <h1>holey demo</h1>\n<p>Models of Srinivasan's <i>Modeling High-Genus Surfaces</i>, built from holey's primitives.\n\
          Each is also written as <code>.obj</code> and <code>.dlfl</code> (which keeps self-loops exactly).</p>\n\
          <table><tr><th>model</th><th>V</th><th>E</th><th>F</th><th>genus</th><th>build ms</th></tr>\n";
    for r in rows {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.1}</td></tr>",
            escape(r.name),
            r.v,
            r.e,
            r.f,
            r.genus,
            r.seconds * 1e3
        );
    }
    h += "</table>\n<div class=\"grid\">\n";
    for r in rows {
        let _ = writeln!(
            h,
            "<figure><a href=\"{n}.png\"><img src=\"{n}.png\" alt=\"{t}\"></a><figcaption><b>{t}</b>{rec}<br>\
             <span class=\"n\">V/E/F {v}/{e}/{f} · genus {g} · {ms:.1} ms · <a href=\"{n}.obj\">obj</a> · <a href=\"{n}.dlfl\">dlfl</a></span></figcaption></figure>",
            n = escape(r.name),
            t = escape(r.title),
            rec = escape(r.recipe),
            v = r.v,
            e = r.e,
            f = r.f,
            g = r.genus,
            ms = r.seconds * 1e3
        );
    }
    h += "</div>\n</body></html>\n";
    h
}

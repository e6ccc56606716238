//! The built-in figures that reproduce the documents' pictures (Snyder's figure 7, June's
//! figures 20.3, 20.9 and 20.17, Arvo's figures 5 and 8, Picott's plates): each a sheet of
//! panels rendered by the scenes of the parent module.

use super::*;

/// A built-in figure: file name, and a function that renders it.
pub struct Figure {
    /// PNG file name.
    pub file: &'static str,
    /// Renders the sheet.
    pub render: fn() -> Result<tiny_skia::Pixmap, RasterError>,
}

/// Every built-in figure.
pub fn figures() -> Vec<Figure> {
    vec![
        Figure {
            file: "snyder_fig7.png",
            render: snyder_fig7,
        },
        Figure {
            file: "june_fig20_3.png",
            render: june_fig20_3,
        },
        Figure {
            file: "june_fig20_9.png",
            render: june_fig20_9,
        },
        Figure {
            file: "june_fig20_17.png",
            render: june_fig20_17,
        },
        Figure {
            file: "arvo_fig5.png",
            render: arvo_fig5,
        },
        Figure {
            file: "arvo_fig8.png",
            render: arvo_fig8,
        },
        Figure {
            file: "picott_plates.png",
            render: picott_plates,
        },
    ]
}

fn snyder_fig7() -> Result<tiny_skia::Pixmap, RasterError> {
    let mut panels = Vec::new();
    for kind in SnyderLight::ALL {
        panels.push(panel(&snyder_scene::<f32>(kind, 220, 180)?, kind.title())?);
    }
    Ok(figure::sheet(
        "Snyder, fig. 7: comparison of area light source results (f32, per-pixel Lambert + Phong)",
        &panels,
        5,
        "same scene and materials; each panel exposed so that the floor at the origin (between the objects) is 80 % of display white before the tone curve (linear to 50 %, compressed above, white at 400 %); Phong m = 8..24",
    ))
}

fn single_sphere<T: Real + 'static>(
    light: Box<dyn Illuminant<T>>,
    exposure: T,
    eye: [f64; 3],
) -> Result<Scene<T>, RasterError> {
    let white = Material::matte(c(1.0, 1.0, 1.0))?;
    Ok(Scene {
        camera: camera(eye, [0.0, 0.0, 0.0], 30.0, 220, 220)?,
        objects: vec![Object::new(
            sphere(1.0, 24, 40)?,
            Affine::identity(),
            Surface::Lit(white),
        )],
        lights: Lights(vec![light]),
        exposure,
        background: [0, 0, 0],
        encoding: Encoding::Srgb,
    })
}

fn june_fig20_3() -> Result<tiny_skia::Pixmap, RasterError> {
    // June's parameters: sky (0.5, 0.5, 1), ground (0.2, 1, 0.2), sky direction +y.
    let sky = SkyGround::new(v(0.0, 1.0, 0.0), c(0.5, 0.5, 1.0), c(0.2, 1.0, 0.2))?;
    let scene = single_sphere::<f32>(Box::new(sky), 1.0, [0.0, 0.0, 4.4])?;
    let mut side = single_sphere::<f32>(
        Box::new(SkyGround::new(
            v(0.0, 1.0, 0.0),
            c(0.5, 0.5, 1.0),
            c(0.2, 1.0, 0.2),
        )?),
        1.0,
        [3.1, 1.6, 2.6],
    )?;
    side.background = [0, 0, 0];
    Ok(figure::sheet(
        "June, fig. 20-3: hemisphere lighting of a sphere",
        &[
            panel(&scene, "sky (.5,.5,1), ground (.2,1,.2)")?,
            panel(&side, "the same, seen from above-right")?,
        ],
        2,
        "sky_ground with the sky toward +y (up), exact (June eq. 20.7); f32, shaded per pixel",
    ))
}

fn june_fig20_9() -> Result<tiny_skia::Pixmap, RasterError> {
    // (a) a white disc of alpha = 20 degrees around +z (toward the viewer), (b) Grace Cathedral.
    let disc = Sh9::<f32>::disc(v(0.0, 0.0, 1.0), 20f32.to_radians(), c(1.0, 1.0, 1.0))?.prepare();
    let grace = Sh9::<f32>::environment(Environment::GraceCathedral).prepare();
    let e_disc = exposure_at(&disc, v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
    let a = single_sphere::<f32>(Box::new(disc), e_disc, [0.0, 0.0, 4.4])?;
    let b = single_sphere::<f32>(Box::new(grace), 1.0, [0.0, 0.0, 4.4])?;
    Ok(figure::sheet(
        "June, fig. 20-9: spherical harmonics lighting",
        &[
            panel(&a, "(a) disc light, alpha = 20 deg, +z")?,
            panel(&b, "(b) Grace Cathedral (Table 20-1)")?,
        ],
        2,
        "sh9_disc_irradiance and sh9_irradiance / pi; (a) exposed x0.8/peak, (b) as June, unscaled",
    ))
}

fn june_fig20_17() -> Result<tiny_skia::Pixmap, RasterError> {
    // June's parameters: light at (1, 1, 2) aimed at the origin, eye at (0, 0, 6.3),
    // a, b, A, B, d = 0.2, 0.3, 0.3, 0.4, 0.8; zNear, zFar = 1, 2; edges 0.4, 0.8;
    // maxIntensity 2, d0 = 1, alpha = 1; shininess 4, ambient (0.5, 0.2, 0.2).
    let pos = v::<f32>(1.0, 1.0, 2.0);
    let frame = LightFrame::new(pos, -pos, v(0.0, 1.0, 0.0))?;
    let shape = Superellipse::new(0.2, 0.3, 0.3, 0.4, 0.8)?;
    let falloff = DistanceFalloff::new(2.0, 1.0, 1.0, 1.0, 2.0, 0.4, 0.8)?;
    let uber = Uberlight::new(frame, shape, falloff);
    let ambient = Ambient(c(0.5, 0.2, 0.2));
    let point = Shaped {
        light: PointLight::new(pos)?,
        shape: uber,
    };
    // The same beam shaping a 0.3 x 0.3 square area light at the same place.
    let (u, w) = (frame.right() * 0.15, frame.up() * 0.15);
    let square =
        PolygonLight::<f32, 4>::new(&[pos - u - w, pos + u - w, pos + u + w, pos - u + w])?;
    let k = 0.8 / (square.lambert(v(0.0, 0.0, 1.0), -frame.direction()) as f64).max(1e-6);
    let area = Shaped {
        light: Tinted::new(square, c(k, k, k))?,
        shape: uber,
    };
    let mk = |lights: Lights<f32>| -> Result<Scene<f32>, RasterError> {
        let white = Material::new(c(1.0, 1.0, 1.0), c(1.0, 1.0, 1.0), 4)?;
        let wall = Material::new(c(0.9, 0.9, 0.9), c(0.2, 0.2, 0.2), 4)?;
        Ok(Scene {
            camera: camera([0.0, 0.0, 6.3], [0.0, 0.0, 0.0], 40.0, 260, 220)?,
            objects: vec![
                Object::new(
                    sphere(1.0, 24, 40)?,
                    Affine::identity(),
                    Surface::Lit(white),
                ),
                Object::new(
                    plane(9.0, 9.0, 12, 12)?,
                    rotate([1.0, 0.0, 0.0], 90.0)?.then(&translate(0.0, 0.0, -1.3)?),
                    Surface::Lit(wall),
                ),
            ],
            lights,
            exposure: 1.0,
            background: [0, 0, 0],
            encoding: figure_tone()?,
        })
    };
    let a = mk(Lights(vec![Box::new(point), Box::new(ambient)]))?;
    let b = mk(Lights(vec![Box::new(area), Box::new(ambient)]))?;
    Ok(figure::sheet(
        "June, fig. 20-17: uberlight-like shader, June's parameters",
        &[
            panel(&a, "(a) point light x shape x falloff + ambient")?,
            panel(&b, "(b) the same beam on a square area light")?,
        ],
        2,
        "superellipse a,b,A,B,d = .2,.3,.3,.4,.8; zones 1..2 (edges .4, .8); falloff M=2, d0=1, alpha=1; tone curve linear to 50 %, white at 400 %",
    ))
}

/// Arvo's window: four panes of a 2x2 window on the wall z = `z`, facing +z.
fn window_panes<T: Real>(z: f64) -> Result<Vec<PolygonLight<T, 4>>, RasterError> {
    let mut panes = Vec::new();
    for (x0, y0) in [(-0.95, 0.55), (0.05, 0.55), (-0.95, 1.65), (0.05, 1.65)] {
        let (x1, y1) = (x0 + 0.9, y0 + 1.0);
        panes.push(PolygonLight::new(&[
            v(x0, y0, z),
            v(x1, y0, z),
            v(x1, y1, z),
            v(x0, y1, z),
        ])?);
    }
    Ok(panes)
}

fn quad_mesh<T: Real>(verts: [Vec3<T>; 4], n: Vec3<T>) -> MeshBuf<T> {
    MeshBuf {
        verts: verts.iter().map(|&p| Vertex::new(p, n)).collect(),
        tris: vec![[0, 1, 2], [0, 2, 3]],
    }
}

fn arvo_fig5() -> Result<tiny_skia::Pixmap, RasterError> {
    // Top row: the luminaire at three orders; bottom row: the glossy floor at three orders.
    let mut panels = Vec::new();
    let mut bottom = Vec::new();
    let orders_l = [1u32, 5, 20];
    let orders_r = [10u32, 50, 200];
    for row in 0..3 {
        // Left: a square luminaire 2 above the floor, facing down, emitting
        // ((-u).axis)^m, scaled by (m + 2)/2 so every order emits the same power.
        let m = orders_l[row];
        let lum = PolygonLight::<f32, 4>::new(&[
            v(-0.6, 2.0, -0.6),
            v(0.6, 2.0, -0.6),
            v(0.6, 2.0, 0.6),
            v(-0.6, 2.0, 0.6),
        ])?;
        let lum_mesh = quad_mesh(
            lum.vertices().try_into().unwrap_or([v(0.0, 0.0, 0.0); 4]),
            v(0.0, -1.0, 0.0),
        );
        let s = (m as f32 + 2.0) / 2.0;
        let light = Tinted::new(
            DirectionalLuminaire::new(lum, v(0.0, -1.0, 0.0), m)?,
            c(s as f64, s as f64, s as f64),
        )?;
        let grey = Material::matte(c(0.7, 0.7, 0.7))?;
        let scene = Scene {
            camera: camera([0.0, 3.4, 4.2], [0.0, 0.4, 0.0], 45.0, 220, 176)?,
            objects: vec![
                Object::new(
                    plane(8.0, 8.0, 8, 8)?,
                    Affine::identity(),
                    Surface::Lit(grey),
                ),
                Object::new(
                    cuboid([0.3, 0.3, 0.3])?,
                    translate(0.9, 0.3, 0.4)?,
                    Surface::Lit(grey),
                ),
                Object {
                    two_sided: true,
                    ..Object::new(
                        lum_mesh,
                        Affine::identity(),
                        Surface::Emissive(c(1.0, 1.0, 0.9)),
                    )
                },
            ],
            lights: Lights(vec![Box::new(light)]),
            exposure: 0.35,
            background: [0, 0, 0],
            encoding: Encoding::Srgb,
        };
        panels.push(panel(&scene, &format!("directional luminaire, order {m}"))?);

        // Right: a glossy floor reflecting a four-pane window (Arvo 6.2), order n.
        let n = orders_r[row];
        let panes = window_panes::<f32>(-2.5)?;
        let glossy: ShadeFn<f32> = Box::new(move |p, nn, e| {
            let mut s = 0.0;
            let mut d = 0.0;
            for pane in &panes {
                s += pane.glossy_reflection(p, nn, e, n);
                d += pane.lambert(p, nn);
            }
            c(0.03, 0.03, 0.035)
                .scale(d)
                .add(c(0.9, 0.85, 0.7).scale(s * 0.5))
        });
        let mut objects = vec![Object::new(
            plane(8.0, 8.0, 1, 1)?,
            Affine::identity(),
            Surface::Custom(glossy),
        )];
        for pane in window_panes::<f32>(-2.5)? {
            let q: [Vec3<f32>; 4] = pane.vertices().try_into().unwrap_or([v(0.0, 0.0, 0.0); 4]);
            objects.push(Object::new(
                quad_mesh(q, v(0.0, 0.0, 1.0)),
                Affine::identity(),
                Surface::Emissive(c(0.9, 0.85, 0.7)),
            ));
        }
        let scene = Scene {
            camera: camera([0.3, 1.1, 3.0], [0.0, 0.5, -1.5], 50.0, 220, 176)?,
            objects,
            lights: Lights(vec![]),
            exposure: 1.0,
            background: [10, 10, 14],
            encoding: Encoding::Srgb,
        };
        bottom.push(panel(&scene, &format!("glossy reflection, order {n}"))?);
    }
    panels.extend(bottom);
    Ok(figure::sheet(
        "Arvo, fig. 5: directional luminaire (top), glossy reflection (bottom)",
        &panels,
        3,
        "top: double-axis moments, emission ((-u).axis)^m x (m+2)/2; bottom: a window's reflection on a glossy floor, (m+2)/2pi int (u.mr)^m (n.u) du",
    ))
}

fn arvo_fig8() -> Result<tiny_skia::Pixmap, RasterError> {
    let mut panels = Vec::new();
    for m in [3u32, 20, 200] {
        // Bright shapes 1.2 behind a frosted pane at z = 0.
        let z = -1.2;
        let shapes: Vec<PolygonLight<f32, 8>> = vec![
            PolygonLight::new(&[v(-1.1, -0.6, z), v(-0.5, -0.6, z), v(-0.8, 0.5, z)])?,
            PolygonLight::new(&[
                v(-0.2, -0.5, z),
                v(0.3, -0.5, z),
                v(0.3, 0.0, z),
                v(0.05, 0.0, z),
                v(0.05, 0.5, z),
                v(-0.2, 0.5, z),
            ])?,
            PolygonLight::new(&[
                v(0.6, -0.4, z),
                v(1.1, -0.4, z),
                v(1.1, 0.4, z),
                v(0.6, 0.4, z),
            ])?,
        ];
        let glass: ShadeFn<f32> = Box::new(move |p, n, e| {
            let mut s = 0.0;
            for sh in &shapes {
                s += sh.glossy_transmission(p, n, e, m);
            }
            c(0.9, 0.95, 1.0).scale(s).add(c(0.02, 0.02, 0.025))
        });
        let pane = Object {
            two_sided: true,
            ..Object::new(
                plane(3.0, 2.2, 1, 1)?,
                rotate([1.0, 0.0, 0.0], 90.0)?,
                Surface::Custom(glass),
            )
        };
        let scene = Scene {
            camera: camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 38.0, 220, 160)?,
            objects: vec![pane],
            lights: Lights(vec![]),
            exposure: 1.4,
            background: [0, 0, 0],
            encoding: figure_tone()?,
        };
        panels.push(panel(&scene, &format!("frosted glass, order {m}"))?);
    }
    Ok(figure::sheet(
        "Arvo, fig. 8: frosted glass (glossy transmission, double-axis moments)",
        &panels,
        3,
        "three emitters 1.2 behind a pane (a triangle, a non-convex L, a rectangle); radiance (m+2)/2pi int (-u.e)^m (-n.u) du; tone curve linear to 50 %, white at 400 %",
    ))
}

fn picott_plates() -> Result<tiny_skia::Pixmap, RasterError> {
    let mut panels = Vec::new();
    for kind in 0..3 {
        let (light, title): (Box<dyn Illuminant<f32>>, &str) = match kind {
            0 => (
                Box::new(PointLight::inverse_square(v(0.0, 2.2, -1.5))?),
                "(a) point light",
            ),
            1 => (
                Box::new(LineLight::new(v(0.0, 2.2, -3.5), v(0.0, 2.2, 0.5))?),
                "(b) linear light (tube along the lane)",
            ),
            _ => (
                Box::new(ParallelogramLight::new(
                    v(-0.7, 2.2, -3.5),
                    v(1.4, 0.0, 0.0),
                    v(0.0, 0.0, 4.0),
                )?),
                "(c) area light (1.4 x 4 panel)",
            ),
        };
        let exposure = exposure_at(&*light, v(0.0, 0.0, -1.5), v(0.0, 1.0, 0.0));
        let lane = Material::new(c(0.75, 0.55, 0.3), c(0.5, 0.5, 0.5), 40)?;
        let gutter = Material::matte(c(0.15, 0.15, 0.17))?;
        let pin = Material::new(c(0.9, 0.9, 0.88), c(0.6, 0.6, 0.6), 30)?;
        let mut objects = vec![
            Object::new(
                plane(1.6, 9.0, 2, 18)?,
                translate(0.0, 0.0, -2.0)?,
                Surface::Lit(lane),
            ),
            Object::new(
                plane(6.0, 9.0, 2, 2)?,
                translate(0.0, -0.05, -2.0)?,
                Surface::Lit(gutter),
            ),
        ];
        // Ten pins in a triangle: a body and a head each.
        for (row, &z) in [-3.0, -3.3, -3.6, -3.9].iter().enumerate() {
            for i in 0..=row {
                let x = (i as f64 - row as f64 / 2.0) * 0.3;
                objects.push(Object::new(
                    sphere(0.1, 10, 16)?,
                    Affine::scale(v(1.0, 1.8, 1.0))?.then(&translate(x, 0.18, z)?),
                    Surface::Lit(pin),
                ));
                objects.push(Object::new(
                    sphere(0.06, 8, 12)?,
                    translate(x, 0.42, z)?,
                    Surface::Lit(pin),
                ));
            }
        }
        // A ball on the lane.
        objects.push(Object::new(
            sphere(0.22, 16, 24)?,
            translate(0.25, 0.22, -0.8)?,
            Surface::Lit(Material::new(c(0.1, 0.15, 0.6), c(0.8, 0.8, 0.8), 60)?),
        ));
        let scene = Scene {
            camera: camera([0.0, 1.2, 2.2], [0.0, 0.2, -2.8], 40.0, 200, 170)?,
            objects,
            lights: Lights(vec![light]),
            exposure,
            background: [8, 8, 10],
            encoding: figure_tone()?,
        };
        panels.push(panel(&scene, title)?);
    }
    Ok(figure::sheet(
        "Picott's plates: one lane under a point, a linear and an area light",
        &panels,
        3,
        "diffuse: point 1/d^2, line_lambert k=2, polygon_lambert; specular: Picott's peaks (line, rect); exposed so the lane under the point light's position is 80 % before the tone curve (linear to 50 %, white at 400 %)",
    ))
}

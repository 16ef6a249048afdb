//! ReSTIR PT's rows of the parameter table (settings.rs), in the Indirect stage, each named
//! `pt_*` (the switch itself is `pt`). Tokens for `settings::gather_rows!`: names such as
//! `ParamKind` resolve in settings.rs, where the table is expanded.

/// Appends these rows to the tokens it is given and hands them to `$then` with the rest of
/// the list (`settings::gather_rows!`).
macro_rules! rows {
    ($then:ident [$($rest:ident),*] $($rows:tt)*) => {
        $then! {
            [$($rest),*] $($rows)*
            Indirect {
                pt: bool = false, ParamKind::Bool, "Indirect (ReSTIR PT)",
                    "Multi-bounce indirect light with path reuse (GRIS / ReSTIR PT, Lin \
                        et al. 2022): each pixel traces one path of up to max_bounces (at \
                        least 2) bounces with next-event estimation and MIS at every vertex \
                        past the first; its sub-paths are the candidates of one path \
                        reservoir, reused over time and space through a shift mapping \
                        (pt_shift) under pairwise MIS. The image is direct (ReSTIR DI) + \
                        indirect; replaces ReSTIR GI while on. Off: no PT code is compiled \
                        or run.";
                pt_shift: PtShift = PtShift::Hybrid, ParamKind::Choice(PT_SHIFT_NAMES), "PT shift mapping",
                    "How a neighbour's path is moved to this pixel. reconnection: keep \
                        its vertices from the second on and connect to it (fails where the \
                        first bounce is glossy: the new angle misses the lobe). \
                        random-replay: trace again with its random numbers (fails when the \
                        replayed path leaves it; exact in glossy chains). hybrid (default): \
                        replay up to the first bounce whose two ends are rough \
                        (pt_rough_threshold) and far enough apart (pt_min_distance), \
                        reconnect there. All three unbiased under pairwise MIS: a path that \
                        cannot be moved is a zero in its domain, never dropped.";
                pt_temporal: bool = true, ParamKind::Bool, "PT temporal reuse",
                    "Merge the reprojected previous-frame path reservoir, its path \
                        shifted from last frame's visible point to this one (and this \
                        pixel's path shifted back there for the pairwise weights). The \
                        previous side is evaluated in this frame's scene: exact for static \
                        scenes; under animation a moving occluder is seen where it is now, \
                        not where it was (named biased, as DI's previous_geometry=false).", ReuseSwitch;
                pt_m_cap: f32 = 10.0, ParamKind::Float { min: 0.0, max: 1e6 }, "PT M cap",
                    "Upper bound of a path reservoir's confidence M. 10, as GI's: a \
                        reconnected path's radiance beyond its reconnection vertex is \
                        cached, not re-evaluated, so it outlives a lighting change for about \
                        M cap frames.";
                pt_spatial: bool = true, ParamKind::Bool, "PT spatial reuse",
                    "Merge the path reservoirs of nearby pixels, each path shifted to \
                        this pixel (and this pixel's path shifted to each of them for the \
                        pairwise weights).", ReuseSwitch;
                pt_spatial_neighbours: u32 = 3, ParamKind::Int { min: 0, max: MAX_SPATIAL_NEIGHBOURS as i64 }, "PT neighbours",
                    "Neighbours tried per pixel in PT spatial reuse; each costs two \
                        shifts (a replayed prefix is up to max_bounces − 1 rays, a \
                        reconnection one visibility ray).";
                pt_spatial_radius: f32 = 30.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "PT radius (px at 1080p)",
                    "Radius of the PT neighbour disk in pixels of a 1080-pixel-high \
                        image, scaled with the height (at least 2 px).";
                pt_rough_threshold: f32 = 0.3, ParamKind::Float { min: 0.0, max: 1.0 }, "PT roughness threshold",
                    "Hybrid shift: a vertex is rough enough to reconnect at when its \
                        material roughness is at least this, or it has no specular lobe. 0: \
                        every vertex (hybrid = reconnection at the first far-enough pair); \
                        1: only purely rough ones.";
                pt_min_distance: f32 = 0.02, ParamKind::Float { min: 0.0, max: 1.0 }, "PT reconnection distance",
                    "Hybrid shift: the two ends of the reconnected segment must be at \
                        least this far apart, as a fraction of the scene's size (the \
                        diagonal of its bounding box, not world units: 0.02 is 2 % of it). A \
                        near reconnection has a Jacobian far from 1.";
                pt_jacobian_clamp: f32 = 0.0, ParamKind::Float { min: 0.0, max: 1000.0 }, "PT Jacobian clamp (biased)",
                    "Biased, off by default (0): clamp every shift's |J| into [1/c, c] (c \
                        ≥ 1). Bounds the fireflies of near or grazing reconnections at the \
                        price of a wrong change of measure: the image is no longer the \
                        integral (measured in docs/src/measured/path-reuse.md, \
                        \"ReSTIR PT on builtin:glossy\").";
            }
        }
    };
}
pub(crate) use rows;

//! Automatic framing: thin models are seen face-on and whole; F keeps the direction.

use glam::{Mat4, Vec3, Vec4Swizzles};

use super::*;

fn slab(extent: Vec3) -> Aabb {
    Aabb {
        min: Vec3::new(1.0, -2.0, 3.0) - extent * 0.5,
        max: Vec3::new(1.0, -2.0, 3.0) + extent * 0.5,
    }
}

fn corners(b: Aabb) -> [Vec3; 8] {
    b.corners()
}

fn view_projection(c: &Camera, aspect: f32) -> Mat4 {
    c.projection_matrix(aspect, 1e-3) * c.view_matrix()
}

/// Every corner in front of the camera and inside the image (NDC x, y in [−1, 1]).
fn all_in_view(c: &Camera, b: Aabb, aspect: f32) -> bool {
    let vp = view_projection(c, aspect);
    corners(b).iter().all(|&p| {
        let clip = vp * p.extend(1.0);
        let ndc = clip.xy() / clip.w;
        clip.w > 0.0 && ndc.x.abs() <= 1.0 + 1e-5 && ndc.y.abs() <= 1.0 + 1e-5
    })
}

/// Area of the box's shadow on the image plane (orthographic along the camera's view
/// direction, from the view matrix): Σ over the three face pairs of face area × |cos|.
fn projected_area(c: &Camera, b: Aabb) -> f32 {
    let view = c.view_matrix();
    // The view direction in world space is −(third row of the view rotation).
    let d = -Vec3::new(view.x_axis.z, view.y_axis.z, view.z_axis.z);
    let e = b.extent();
    d.x.abs() * e.y * e.z + d.y.abs() * e.x * e.z + d.z.abs() * e.x * e.y
}

fn largest_face(b: Aabb) -> f32 {
    let e = b.extent();
    (e.x * e.y).max(e.y * e.z).max(e.x * e.z)
}

/// How much of the image the corners' NDC bounding rectangle spans along its longer
/// direction (1 = edge to edge): a framed model fills the image one way or the other.
fn image_fill(c: &Camera, b: Aabb, aspect: f32) -> f32 {
    let vp = view_projection(c, aspect);
    let ndc: Vec<_> = corners(b)
        .iter()
        .map(|&p| {
            let clip = vp * p.extend(1.0);
            clip.xy() / clip.w
        })
        .collect();
    let min = ndc.iter().fold(Vec2::splat(f32::MAX), |a, p| a.min(*p));
    let max = ndc.iter().fold(Vec2::splat(f32::MIN), |a, p| a.max(*p));
    let size = (max.min(Vec2::ONE) - min.max(-Vec2::ONE)).max(Vec2::ZERO);
    size.x.max(size.y) / 2.0
}

use glam::Vec2;

/// The framing before the automatic camera (docs/src/scenes.md, "Cameras") took the larger
/// side (+Z side, slightly above, bounding sphere): the planted twin.
fn old_framing(bounds: Aabb) -> Camera {
    let yfov = 45f32.to_radians();
    let center = bounds.center();
    let radius = bounds.extent().length() * 0.5;
    let distance = radius / (yfov * 0.5).sin() * 1.05;
    let dir = Vec3::new(0.0, 0.25, 1.0).normalize();
    Camera::look_at(center + dir * distance, center, yfov)
}

fn seen_face_on(c: &Camera, b: Aabb) -> bool {
    projected_area(c, b) >= 0.5 * largest_face(b)
}

#[test]
fn thin_standing_models_are_seen_face_on_and_whole() {
    let aspect = 16.0 / 9.0;
    for extent in [
        Vec3::new(10.0, 10.0, 0.1), // standing in the XY plane
        Vec3::new(0.1, 10.0, 10.0), // the same turned into the YZ plane
        Vec3::new(10.0, 0.1, 10.0), // lying flat
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(40.0, 1.0, 3.0),
    ] {
        let b = slab(extent);
        let c = Camera::framing(b);
        assert!(
            seen_face_on(&c, b),
            "{extent}: {} of {}",
            projected_area(&c, b),
            largest_face(b)
        );
        assert!(
            all_in_view(&c, b, aspect),
            "{extent}: not all corners in view"
        );
        assert!(all_in_view(&c, b, 1.0), "{extent}: not all in view at 1:1");
        assert!(
            image_fill(&c, b, aspect) > 0.4,
            "{extent}: {}",
            image_fill(&c, b, aspect)
        );
        let elevation = (-c.forward().y).asin().to_degrees();
        assert!(
            (15.0..=65.0).contains(&elevation),
            "{extent}: looks down {elevation}°"
        );
    }
    // Planted twin: the old +Z framing sees the YZ slab edge-on.
    let yz = slab(Vec3::new(0.1, 10.0, 10.0));
    assert!(!seen_face_on(&old_framing(yz), yz));
    assert!(seen_face_on(
        &old_framing(slab(Vec3::new(10.0, 10.0, 0.1))),
        slab(Vec3::new(10.0, 10.0, 0.1))
    ));
}

#[test]
fn framing_from_the_current_direction_keeps_it_and_fits_all_corners() {
    let b = slab(Vec3::new(4.0, 1.0, 0.5));
    for (position, aspect) in [
        (Vec3::new(30.0, 5.0, -7.0), 16.0 / 9.0),
        (Vec3::new(1.2, -1.9, 3.4), 1.0), // inside the box: moves out
        (Vec3::new(-3.0, 40.0, 2.0), 0.5),
    ] {
        let start = Camera::look_at(position, Vec3::new(0.0, 0.0, 1.0), 50f32.to_radians());
        let framed = frame_from_direction(&start, b, aspect);
        assert!(all_in_view(&framed, b, aspect), "{position}");
        assert_eq!(framed.rotation, start.rotation);
        assert_eq!(framed.yfov, start.yfov);
        assert!(framed.forward().dot(start.forward()) > 0.999_999);
        // Looks at the centre: the centre projects to the middle of the image.
        let vp = view_projection(&framed, aspect);
        let clip = vp * b.center().extend(1.0);
        assert!((clip.xy() / clip.w).length() < 1e-4, "{position}");
        // Tight: 20 % closer some corner leaves the image.
        let closer = Camera {
            position: b.center() + (framed.position - b.center()) * 0.8,
            ..framed
        };
        assert!(!all_in_view(&closer, b, aspect), "{position}: not tight");
    }
}

//! The Camera panel: position and orientation (editable, copyable), speed, reset to the
//! scene camera, saved viewpoints, and the automatic orbit/dolly.

use egui::Ui;

use crate::viewer::camera::CameraState;

pub fn ui(ui: &mut Ui, camera: &mut CameraState) {
    ui.weak(
        "WASD move · Q/E or Ctrl/Space down/up · right-drag look · wheel speed · Shift faster · \
         F frames the scene",
    );
    if camera.automatic {
        ui.label("Scene camera: chosen automatically (the file has no camera)");
    }
    ui.horizontal(|ui| {
        // The label names the three fields for screen readers (and the UI tests' checks).
        let label = ui.label("Position").id;
        let step = (camera.scale * 0.002) as f64;
        for c in [
            &mut camera.camera.position.x,
            &mut camera.camera.position.y,
            &mut camera.camera.position.z,
        ] {
            ui.add(egui::DragValue::new(c).speed(step).max_decimals(3))
                .labelled_by(label);
        }
    });
    let (yaw, pitch) = camera.yaw_pitch_degrees();
    ui.label(format!("Yaw {yaw:.1}° · pitch {pitch:.1}°"));
    ui.horizontal(|ui| {
        let mut fov = camera.camera.yfov.to_degrees();
        if ui
            .add(
                egui::Slider::new(&mut fov, 10.0..=120.0)
                    .text("Vertical FOV °")
                    .max_decimals(1),
            )
            .changed()
        {
            camera.camera.yfov = fov.to_radians();
        }
    });
    ui.horizontal(|ui| {
        ui.label("Speed");
        ui.add(
            egui::DragValue::new(&mut camera.speed)
                .speed(camera.scale * 0.01)
                .range(camera.scale * 1e-4..=camera.scale * 100.0)
                .suffix(" /s"),
        );
    });
    ui.horizontal(|ui| {
        if ui.button("Reset to scene camera").clicked() {
            camera.reset();
        }
        if ui
            .button("Copy")
            .on_hover_text("Copy position, rotation and field of view as text")
            .clicked()
        {
            ui.ctx().copy_text(camera.describe());
        }
    });
    viewpoints(ui, camera);
    auto_motion(ui, camera);
}

fn viewpoints(ui: &mut Ui, camera: &mut CameraState) {
    ui.horizontal(|ui| {
        ui.label("Viewpoints");
        if ui.small_button("Save current").clicked() {
            camera.save_viewpoint();
        }
    });
    let mut remove = None;
    for (i, v) in camera.viewpoints.iter().enumerate() {
        ui.horizontal(|ui| {
            if ui
                .button(&v.name)
                .on_hover_text("Go to this viewpoint")
                .clicked()
            {
                camera.camera = v.camera;
            }
            if ui.small_button("Forget").clicked() {
                remove = Some(i);
            }
        });
    }
    if let Some(i) = remove {
        camera.viewpoints.remove(i);
    }
}

fn auto_motion(ui: &mut Ui, camera: &mut CameraState) {
    let m = &mut camera.motion;
    ui.horizontal(|ui| {
        ui.checkbox(&mut m.orbit, "Orbit").on_hover_text(
            "Turn about the vertical axis through the scene centre every frame (ghosting)",
        );
        ui.add(
            egui::DragValue::new(&mut m.orbit_degrees)
                .speed(0.05)
                .range(-10.0..=10.0)
                .suffix("°/frame"),
        );
    });
    ui.horizontal(|ui| {
        ui.checkbox(&mut m.dolly, "Dolly")
            .on_hover_text("Move toward and away from the scene centre (disocclusion, boiling)");
        ui.add(
            egui::DragValue::new(&mut m.dolly_amount)
                .speed(0.01)
                .range(0.0..=1.0)
                .prefix("± ")
                .suffix(" × size"),
        );
        ui.add(
            egui::DragValue::new(&mut m.dolly_period)
                .speed(1.0)
                .range(4..=10_000)
                .suffix(" frames"),
        );
    });
}

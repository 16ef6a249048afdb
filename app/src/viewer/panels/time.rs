//! The Time section: play/pause, step one frame, scrub, speed, loop, the clip and the
//! current time. Camera and time are independent; the inspector's freeze freezes both.

use egui::Ui;

use crate::viewer::state::TimeState;

pub fn ui(ui: &mut Ui, time: &mut TimeState) {
    if time.duration <= 0.0 {
        ui.weak("This scene does not change with time.");
        return;
    }
    ui.horizontal(|ui| {
        let label = if time.playing { "Pause" } else { "Play" };
        if ui
            .button(label)
            .on_hover_text("Run scene time (Space is the camera's)")
            .clicked()
        {
            time.playing = !time.playing;
        }
        if ui
            .button("Step")
            .on_hover_text("Advance scene time by one frame (1/30 s) and pause")
            .clicked()
        {
            time.playing = false;
            time.step = true;
        }
        ui.checkbox(&mut time.looping, "Loop")
            .on_hover_text("Wrap at the end of the longest clip; off stops there");
    });
    ui.add(
        egui::Slider::new(&mut time.time, 0.0..=time.duration)
            .text("Time (s)")
            .max_decimals(3),
    )
    .on_hover_text("Scrub: reuse keeps its history across the jump, so lag shows");
    ui.add(
        egui::Slider::new(&mut time.speed, TimeState::SPEED_RANGE)
            .logarithmic(true)
            .text("Speed")
            .max_decimals(2),
    );
    let mut locked = time.frame_fps.is_some();
    if ui
        .checkbox(&mut locked, "Frame-locked (1/30 s per frame)")
        .on_hover_text("While playing, advance time by one 30 fps frame per rendered frame, as `render --fps 30` does, so a lag counts the same frames on any machine; off follows the wall clock")
        .changed()
    {
        time.frame_fps = locked.then_some(30.0);
    }
    if time.clips.len() > 1 {
        let selected = time
            .clip
            .and_then(|c| time.clips.get(c).cloned())
            .unwrap_or_else(|| "all clips".to_string());
        egui::ComboBox::from_label("Clip")
            .selected_text(selected)
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut time.clip, None, "all clips");
                for (i, name) in time.clips.iter().enumerate() {
                    ui.selectable_value(&mut time.clip, Some(i), name);
                }
            });
    }
    ui.weak(format!(
        "t = {:.3} s of {:.3} s{}",
        time.time,
        time.duration,
        if time.playing {
            ", playing"
        } else {
            ", paused"
        }
    ));
}

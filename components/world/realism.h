#pragma once

#include <random>

#include "world/camera_renderer.h"
#include "world/world.h"

namespace stickrep::world {

// The clutter of real hallway frames that a clean render lacks (real webcam
// frames of hallways with doors). Each feature is a switch; every random choice comes from
// the caller's seeded generator, so a seed gives the same building, camera and light.
// Values not in the text are marked as ours.
struct RealismOptions {
  // Baseboards: a dark strip at the foot of every wall; seen obliquely its top edge is the
  // perspective diagonal that chains neighbouring edges in full-frame mode.
  bool baseboards = true;
  double baseboard_height_in = 4.0;  // World's default
  int baseboard_intensity = 50;

  // A glossy floor mirrors doors and lights (World::floor_reflectance).
  bool floor_reflections = false;
  double floor_reflectance = 0.3;

  // Ceiling light strips: luminaires every light_spacing_in along each wall, their centre
  // light_offset_in in front of its face.
  bool ceiling_lights = false;
  double light_spacing_in = 96.0;
  double light_offset_in = 30.0;
  double light_length_in = 48.0;
  double light_width_in = 12.0;

  // Notice boards and posters: high-contrast rectangles 20-40 in wide on the wall between
  // doors, one per notice_board_spacing_in of free wall on average; a share of them glazed
  // (a bright pane inside a dark frame).
  bool notice_boards = false;
  double notice_board_spacing_in = 120.0;
  double min_board_width_in = 20.0;
  double max_board_width_in = 40.0;
  double glazed_share = 0.4;

  // Light pilasters and wall panels between doors: the wall between two doors closer than
  // pilaster_max_gap_in (casing to casing) carries a light full-height strip, a pilaster
  // (8-16 in) or a panel over the whole gap, and the doors either side are dark.
  bool pilasters = false;
  double pilaster_max_gap_in = 60.0;

  // Door appearance: a share of doors dark wood with dark casings, a share white on the
  // white wall where only a faint casing shows; the rest keep the template's look.
  bool door_appearance = false;
  double dark_door_share = 0.4;
  double white_door_share = 0.2;

  // Doors ajar: a share of the closed doors opened a few degrees into the room.
  bool doors_ajar = false;
  double ajar_share = 0.2;
  double max_ajar_deg = 12.0;

  // The camera as real ones are mounted: roll and pitch misalignment and lens distortion
  // drawn once per camera. Real hallway frames show door edges leaning 6-8 px over 400
  // rows (about 1 deg of roll); webcam lenses range from barrel to the 6 mm lens's
  // pincushion (§4.1.1).
  bool camera_misalignment = false;
  double max_roll_deg = 1.5;
  double max_pitch_deg = 3.0;
  double min_k1 = -0.08;
  double max_k1 = 0.10;

  // Illumination: gain, offset, horizontal and vertical gradients and vignetting drawn
  // per frame, and sensor noise within [min_noise, max_noise] grey levels.
  bool illumination = false;
  double min_gain = 0.6, max_gain = 1.2;
  double max_offset = 15.0;
  double max_gradient = 0.4;
  double max_vertical_gradient = 0.3;
  double max_vignetting = 0.35;
  double min_noise = 1.5, max_noise = 4.0;
};

// Every switch on (the defaults of each feature).
RealismOptions FullRealism();
// The clean renders of before: every switch off but the baseboards, which World always had.
RealismOptions CleanRender();

// Throws std::invalid_argument with the field and its range on a bad value.
void ValidateRealism(const RealismOptions& options);

// Adds the scene features that are switched on to `world`: baseboards, floor gloss,
// ceiling lights, notice boards, pilasters, door looks, doors ajar. Walls shorter than a
// foot get no lights or boards. Draws only from `rng`.
void ApplyRealism(const RealismOptions& options, std::mt19937_64& rng, World* world);

// The camera's misalignment and lens, drawn when switched on (else `camera` unchanged).
CameraModel DrawCamera(const RealismOptions& options, CameraModel camera, std::mt19937_64& rng);

// One frame's light: drawn when illumination is on, else `base` unchanged.
Illumination DrawIllumination(const RealismOptions& options, const Illumination& base,
                              std::mt19937_64& rng);

}  // namespace stickrep::world

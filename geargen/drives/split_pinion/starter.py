"""The split pinion's starters for ``geargen new split_pinion`` (metric) and ``--units in`` (inch).

``METRIC``: a Type 1 concentric split pinion like ``assemblies/split_pinion.toml`` at another size
(module 1 mm, 24/96, 4:1), its inner shaft sized for the preload band. ``INCH``: the inch split pinion
of ``assemblies/split_pinion_inch.toml`` (20 diametral pitch, 18/90). Both pass ``geargen check`` and
build (tests/test_new.py).
"""

from __future__ import annotations

from geargen.design.starters import Key, Starter, Table

METRIC = Starter(
    "split_pinion",
    "a Type 1 concentric split pinion (Hale & Slocum 1994, Fig. 8), metric",
    "The structure of assemblies/split_pinion.toml at another size: module 1 mm, two 24-tooth pinions side by "
    "side on one 96-tooth output (4:1). The stiff path is a wide pinion on a hollow shaft; the compliant path a "
    "narrow pinion on an inner shaft that runs through the hollow one to a clamp collar, the frictional "
    "interface where the preload is set (wind the inner shaft, then clamp). The inner shaft's torsion is the "
    "loop's compliance, sized below for the loop errors.",
    (
        Table("", (
            Key("description", "Metric Type 1 split pinion with a frictional-interface preload (geargen starter)"),
            Key("length_unit", "mm"),
        )),
        Table("drive", (
            Key("type", "type1", "the compliant path carries the preload only, the stiff one the load"),
            Key("preload", "frictional_interface"),
        )),
        Table("gear_defaults", (
            Key("module_mm", 1.0),
            Key("pressure_angle_deg", 20),
        )),
        Table("gears.pinion_stiff", (
            Key("teeth", 24),
            Key("face_width_mm", 10, "carries the drive load"),
            Key("bore_diameter_mm", 12, "on the hollow shaft (= [parts] hollow_shaft_outer_diameter)"),
        ), "outer (stiff) path"),
        Table("gears.pinion_compliant", (
            Key("teeth", 24),
            Key("face_width_mm", 6, "carries the preload only: a narrower face"),
            Key("bore_diameter_mm", 6.5, "the inner shaft fills it (its one home)"),
        ), "inner (compliant) path"),
        Table("gears.output", (
            Key("teeth", 96, "4:1 with either pinion"),
            Key("face_width_mm", 18, "spans both pinions: 10 + 2 gap + 6"),
            Key("bore_diameter_mm", 20),
        )),
        Table("stiffness", (
            Key("elastic_modulus_GPa", 207),
            Key("shear_modulus_GPa", 79.3),
            Key("reduce_to", "output", "the split pinion of [layout]: each component sits on the shaft or the gear "
                "it names, whose speed comes from the teeth (\"input\", the pinions' shaft, turns 96 / 24 = 4 times "
                "the output)"),
        ), "Inner shaft sizing. Loop error (runout of the two pinion halves against each other plus "
           "tooth-to-tooth, about 20 um at the output's 48 mm pitch radius): 400 urad at the output. Preload "
           "9 N·m (a little above the 8 N·m maximum load: the paper's rule for Type 1); preload band 20 % peak "
           "to peak: k_L = 0.2 x 9 / 400e-6 = 4500 N·m/rad at the output, 281 N·m/rad on the pinion shaft "
           "(ratio 4 squared). The compliant path is almost all shaft, so G J / L = 281 N·m/rad with L = 60 mm "
           "gives d = (32 x 281e3 x 60 / (pi x 79.3e3))^(1/4) = 6.8 mm: 6.5 mm, a little softer. "
           "With each pinion's support (below) geargen stiffness shows the band: 8.5 to 9.5 N·m (12 %)."),
        Table("stiffness.components.mesh_stiff", (
            Key("kind", "mesh"),
            Key("gears", ["pinion_stiff", "output"]),
            Key("scope", "path1"),
        )),
        Table("stiffness.components.mesh_compliant", (
            Key("kind", "mesh"),
            Key("gears", ["pinion_compliant", "output"]),
            Key("scope", "path2"),
        )),
        Table("stiffness.components.hollow_shaft", (
            Key("kind", "shaft_torsion"),
            Key("gear", "pinion_stiff"),
            Key("from_geometry", True, "the placed hollow shaft: its lower end, where the drive turns it, to the "
                "wide pinion's mid-face"),
            Key("scope", "path1"),
        ), "the stiff path's shaft between the input and the wide pinion"),
        Table("stiffness.components.inner_shaft", (
            Key("kind", "shaft_torsion"),
            Key("gear", "pinion_compliant"),
            Key("from_geometry", True, "d = the narrow pinion's bore, L = 60 mm from [parts]"),
            Key("scope", "path2"),
        ), "the compliant path: the placed inner shaft, collar face to narrow pinion"),
        Table("stiffness.components.stiff_support", (
            Key("kind", "shaft_support"),
            Key("gear", "pinion_stiff"),
            Key("from_geometry", True, "overhangs its bearing pair (20 mm apart) by 8.5 mm"),
            Key("stiffness_N_per_um", 40, "per bearing, radial"),
            Key("scope", "path1"),
        ), "each pinion on its placed shaft and supports"),
        Table("stiffness.components.compliant_support", (
            Key("kind", "shaft_support"),
            Key("gear", "pinion_compliant"),
            Key("from_geometry", True, "between the clamp collar and the outboard bearing"),
            Key("stiffness_N_per_um", 40),
            Key("scope", "path2"),
        )),
        Table("preload", (
            Key("max_output_torque_Nm", 8),
            Key("preload_Nm", 9, "a little above the maximum load (Type 1)"),
            Key("loop_error_rotation_urad", 400, "anticipated loop error at the output, peak to peak"),
        )),
        Table("layout", (
            Key("kind", "split_pinion"),
            Key("model_tooth_thickness", "mid_tolerance"),
            Key("loaded_flank_gap_mm", 0.0005, "0.5 um, so that the solids do not touch"),
            Key("centre_distance_mm", 60.0, "standard (24 + 96) x 1 / 2"),
            Key("pinion_axial_gap_mm", 2),
            Key("circumferential_backlash_min_mm", 0.04, "each pinion's own mesh with the output"),
            Key("circumferential_backlash_max_mm", 0.08),
        ), "The assembly model (geargen build): placement, the other parts, exports."),
        Table("parts", (
            Key("bearing_clearance_mm", 0.5),
            Key("hollow_shaft_outer_diameter_mm", 12),
            Key("hollow_shaft_length_mm", 58, "the inner shaft then twists over 60 mm, collar to narrow pinion"),
            Key("bearing_outer_diameter_mm", 24, "61901-size pair, 12 x 24 x 6 mm, preloaded"),
            Key("bearing_width_mm", 6),
            Key("bearing_spacing_mm", 20, "a spacer between the pair, so the wide pinion overhangs a 20 mm base"),
            Key("collar_outer_diameter_mm", 22, "clamp collar: the frictional interface"),
            Key("collar_width_mm", 8),
            Key("collar_slot_mm", 1.2),
            Key("compliant_bearing_outer_diameter_mm", 19, "outboard bearing above the narrow pinion, 6.5 x 19 x 6"),
            Key("compliant_bearing_width_mm", 6),
            Key("output_shaft_diameter_mm", 20, "= the output gear's bore"),
            Key("output_bearing_outer_diameter_mm", 32, "61804-size, 20 x 32 x 7 mm"),
            Key("output_bearing_width_mm", 7),
        )),
        Table("export", (
            Key("stl_chordal_tolerance_mm", 0.005, "gear STL within 5 um of the exact flanks"),
            Key("stl_chordal_tolerance_parts_mm", 0.05),
            Key("stl_angular_tolerance_deg", 30),
            Key("render_view", [-55, 30]),
        )),
    ))

INCH = Starter(
    'split_pinion',
    "a Type 1 concentric split pinion (Hale & Slocum 1994, Fig. 8), in inches",
    "The structure of assemblies/split_pinion.toml in inches (assemblies/split_pinion_inch.toml): 20 diametral "
    "pitch, two 18-tooth pinions side by side on one 90-tooth output (5:1), stock fractional sizes. The stiff "
    "path is a wide pinion on a hollow shaft; the compliant path a narrow pinion on an inner shaft that runs "
    "through the hollow one to a clamp collar, the frictional interface where the preload is set (wind the inner "
    "shaft, then clamp). The inner shaft's torsion is the loop's compliance, sized below for the loop errors.",
    (
        Table('', (
            Key('description',
                "Type 1 split pinion in inches, 20 DP 18/90 (5:1): stiff outer path, compliant inner shaft with a"
                " frictional interface (Hale & Slocum 1994, Fig. 8)"),
            Key('length_unit', "in"),
        )),
        Table('drive', (
            Key('type', "type1"),
            Key('preload', "frictional_interface"),
        )),
        Table('gear_defaults', (
            Key('diametral_pitch_per_in', 20, "module 1.27 mm"),
            Key('pressure_angle_deg', 20, "18 teeth stay above the 20 deg undercut limit (17.1)"),
        )),
        Table('gears.pinion_stiff', (
            Key('teeth', 18),
            Key('face_width_in', 0.5),
            Key('bore_diameter_in', 0.5, "on the hollow shaft"),
        ), "The 18-tooth pinion's root diameter is 0.775 in (0.9 - 2 x 1.25 / 20): the hollow shaft it sits on is"
           " 1/2 in, leaving a 0.1375 in rim under the teeth, 1.2 tooth depths (0.1125 in). The wide pinion "
           "carries the preload and most of the load: at most 132 + 120 x 0.86 = 236 in·lbf at the output, 466 N "
           "at its pitch circle, 93 MPa (Lewis) on its 1/2 in face. outer path: carries the drive load"),
        Table('gears.pinion_compliant', (
            Key('teeth', 18),
            Key('face_width_in', 0.1875),
            Key('bore_diameter_in', 0.25, "the inner shaft fills this bore (its one home)"),
        ), "The narrow pinion carries the preload and a small share of the load: at most 132 + 120 x 0.14 = 148 "
           "in·lbf at the output, 293 N at its pitch circle, a Lewis stress of 293 / (4.76 x 1.27 x 0.309) = 157 "
           "MPa on its 3/16 in face (hardened alloy steel). 3/16 rather than 1/4 in: at the preload's mesh force "
           "the inner shaft tilts it about 1700 urad, 8 um across 3/16 in (12 um across 1/4 in). inner path: "
           "carries the preload only, so a narrower face"),
        Table('gears.output', (
            Key('teeth', 90, "5:1 with either pinion"),
            Key('face_width_in', 0.75, "spans both pinions (0.5 + 0.0625 gap + 0.1875)"),
            Key('bore_diameter_in', 1.0),
        )),
        Table('stiffness', (
            Key('elastic_modulus_GPa', 207),
            Key('shear_modulus_GPa', 79.3),
            Key('reduce_to', "output"),
        ), "Inner shaft sizing. Anticipated loop error (runout of the two pinion halves against each other plus "
           "tooth-to-tooth, ~0.001 in at the output's 2.25 in pitch radius): 444 urad at the output. Preload 132 "
           "in·lbf = 14.9 N·m (10 % above the 120 in·lbf = 13.6 N·m maximum load, the paper's rule for Type 1); "
           "allowed preload band 20 % peak to peak: k_L = 0.2 x 14.9 / 444e-6 = 6720 N·m/rad at the output, 269 "
           "N·m/rad on the pinion shaft (ratio 5, squared 25). The compliant path is almost all shaft (its mesh "
           "is 50x stiffer), so G J / L = 269 N·m/rad with L = 2.5 in = 63.5 mm (about the shortest the hollow "
           "shaft allows: see [parts]) gives d = (32 x 269e3 x 63.5 / (pi x 79.3e3))^(1/4) = 6.84 mm = 0.269 in: "
           "1/4 in stock, a little softer. `geargen stiffness` and the build report show the resulting band."),
        Table('stiffness.components.mesh_stiff', (
            Key('kind', "mesh"),
            Key('gears', ['pinion_stiff', 'output']),
            Key('scope', "path1"),
        ), "the split pinion of [layout]: each component sits on the shaft or the gear it names, whose speed "
           "comes from the teeth (\"input\", the pinions' shaft, turns 90 / 18 = 5 times the output)"),
        Table('stiffness.components.mesh_compliant', (
            Key('kind', "mesh"),
            Key('gears', ['pinion_compliant', 'output']),
            Key('scope', "path2"),
        )),
        Table('stiffness.components.hollow_shaft', (
            Key('kind', "shaft_torsion"),
            Key('gear', "pinion_stiff"),
            Key('from_geometry', True, "0.5 / 0.29 in: the placed hollow shaft (geargen.model.shafts)"),
            Key('scope', "path1"),
        ), "The drive turns the hollow shaft at its lower end, where the clamp collar joins the inner shaft to it"
           " (the coupling is not modelled): path 1 twists the hollow shaft from there to the wide pinion's mid-"
           "face (2.4375 - half the 0.5 in face = 2.1875 in), path 2 the inner shaft from the collar's face to "
           "the narrow pinion; they share none of it. the stiff path's shaft between the input and the wide "
           "pinion"),
        Table('stiffness.components.inner_shaft', (
            Key('kind', "shaft_torsion"),
            Key('gear', "pinion_compliant"),
            Key('from_geometry', True, "d = the pinion's bore, L = 2.5 in from [parts] (geargen.model.shafts)"),
            Key('scope', "path2"),
        ), "the compliant path: the placed inner shaft, collar face to narrow pinion"),
        Table('stiffness.components.stiff_support', (
            Key('kind', "shaft_support"),
            Key('gear', "pinion_stiff"),
            Key('from_geometry', True),
            Key('stiffness_N_per_um', 30),
            Key('scope', "path1"),
        ), "Each pinion on its shaft and supports (from the placed geometry): the wide pinion overhangs its "
           "preloaded bearing pair (1.5 in apart) by 0.43 in; the narrow one sits between the clamp collar (on "
           "the hollow shaft's overhung end) and its outboard bearing. Radial stiffness per bearing: 30 N/um for "
           "the preloaded 1/2 in pair, 20 N/um for the small outboard R4 (which the collar's support, the hollow "
           "shaft on its pair, is then also taken at: one number per component, on the soft side). The pair's 1.5"
           " in base keeps the wide pinion's tilt at the preload's 278 N mesh force under 10 um across its face "
           "(1 in apart it was about 11 um)."),
        Table('stiffness.components.compliant_support', (
            Key('kind', "shaft_support"),
            Key('gear', "pinion_compliant"),
            Key('from_geometry', True),
            Key('stiffness_N_per_um', 20),
            Key('scope', "path2"),
        )),
        Table('duty', (
            Key('material', "case_carburised",
                "The load spectrum defaults to [preload] max_output_torque both ways for the whole life (60 rpm, "
                "20,000 h). At this size the stiff path needs case carburised gears of the best quality (ISO "
                "6336-5 ME), ground after hardening (ISO 1328 class 5, R_a 0.4 um): with MQ or hobbed flanks S_H "
                "< 1 (geargen check names this fix when the material is left out)."),
            Key('quality', "ME"),
            Key('accuracy_grade', 5),
            Key('roughness_Ra_um', 0.4),
        )),
        Table('preload', (
            Key('max_output_torque_in_lbf', 120),
            Key('preload_in_lbf', 132, "10 % above the maximum load (Type 1)"),
            Key('loop_error_rotation_urad', 444, "anticipated loop error at the output, peak to peak"),
        )),
        Table('layout', (
            Key('kind', "split_pinion"),
            Key('model_tooth_thickness', "mid_tolerance"),
            Key('loaded_flank_gap_in', 2e-05, "0.5 um left on the working flanks so the solids do not touch"),
            Key('centre_distance_in', 2.7, "standard (18 + 90) / (2 x 20)"),
            Key('pinion_axial_gap_in', 0.0625),
            Key('circumferential_backlash_min_in', 0.0015, "each pinion's own mesh with the output (thinned pinions)"),
            Key('circumferential_backlash_max_in', 0.003),
        )),
        Table('parts', (
            Key('bearing_clearance_in', 0.02),
            Key('hollow_shaft_outer_diameter_in', 0.5),
            Key('hollow_shaft_length_in', 2.4375,
                "through the wide pinion, its bearing pair and their spacing (0.5 + 0.02 + 0.3125 + 1.5 = 2.33 "
                "in) and 0.1 in beyond; the inner shaft then twists over 2.4375 + the 1/16 in pinion gap = 2.5 "
                "in, collar to narrow pinion"),
            Key('bearing_outer_diameter_in', 1.125, "R8-size pair, preloaded (1/2 x 1 1/8 x 5/16)"),
            Key('bearing_width_in', 0.3125),
            Key('bearing_spacing_in', 1.5, "a spacer between the pair: the wide pinion overhangs a 1.5 in base"),
            Key('collar_outer_diameter_in', 0.875, "clamp collar: the frictional interface"),
            Key('collar_width_in', 0.375),
            Key('collar_slot_in', 0.05),
            Key('compliant_bearing_outer_diameter_in', 0.625,
                "outboard bearing above the narrow pinion, R4 (1/4 x 5/8 x 0.196)"),
            Key('compliant_bearing_width_in', 0.196),
            Key('housing_margin_in', 0.2, "plate material around the outermost bearing seats"),
            Key('output_shaft_diameter_in', 1.0),
            Key('output_bearing_outer_diameter_in', 1.5, "thin-section bearing, 1 x 1.5 x 0.25"),
            Key('output_bearing_width_in', 0.25),
        )),
        Table('export', (
            Key('stl_chordal_tolerance_in', 0.0004, "gear STL within 10 um of the exact flanks"),
            Key('stl_chordal_tolerance_parts_in', 0.002),
            Key('render_view', [-55, 30]),
        )),
    ),
    units="in",
)

#: the kind's starters by length unit
STARTERS = {"mm": METRIC, "in": INCH}

__all__ = ["METRIC", "INCH", "STARTERS"]

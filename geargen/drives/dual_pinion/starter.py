"""The dual pinion's starters for ``geargen new dual_pinion`` (metric) and ``--units in`` (inch).

``METRIC``: a Type 2 dual-pinion drive with radial preload on blade flexures and springs, laid out like
``assemblies/robot_joint.toml`` but metric (module 1 mm) with its own tooth train (18/54 and 20/100,
15:1). ``INCH``: the robot joint itself (32 diametral pitch, inch parts). Both pass ``geargen check``
and build (tests/test_new.py).
"""

from __future__ import annotations

from geargen.design.starters import Key, Starter, Table

METRIC = Starter(
    "dual_pinion",
    "a Type 2 dual-pinion drive with radial preload (Hale & Slocum 1994, Fig. 10), metric",
    "The structure of assemblies/robot_joint.toml (a robot revolute joint: the input pinion rides on blade "
    "flexures and is pushed between two cluster gears by two springs), metric and with its own tooth train: "
    "module 1 mm, 18/54 then 20/100, 15:1, and 30:1 from the motor through a 2:1 bevel pair. Every value is a "
    "consistent starting point, not a finished design: change the gears first, then run geargen synth, "
    "check and stiffness again.",
    (
        Table("", (
            Key("description", "Metric dual-pinion Type 2 drive with radial-motion preload (geargen starter)"),
            Key("length_unit", "mm"),
        )),
        Table("drive", (
            Key("type", "type2", "both paths carry the load alike; the preload must be at least half the maximum load"),
            Key("preload", "radial", "the input pinion moves on its carriage between the two cluster gears"),
        )),
        Table("gear_defaults", (
            Key("module_mm", 1.0, "about the robot joint's 32 DP (0.79 mm) scaled up, so the 20-tooth cluster "
                "pinion keeps a root around an 8 mm shaft"),
            Key("pressure_angle_deg", 20),
        )),
        Table("gears.input", (
            Key("teeth", 18, "18 teeth at 20 deg are not undercut (the limit is 17)"),
            Key("face_width_mm", 8, "wider than the cluster's large gear so the carriage's axial play keeps "
                "the full contact"),
            Key("bore_diameter_mm", 5, "on the 5 mm input shaft from the bevel gear"),
        ), "gear 1: the input pinion, on the symmetry line, on the flexure carriage"),
        Table("gears.cluster_large", (
            Key("teeth", 54, "mesh 1 is 54 / 18 = 3:1"),
            Key("face_width_mm", 6),
            Key("bore_diameter_mm", 8, "pressed and bonded on the 8 mm cluster shaft"),
        ), "gear 2: the large gear of each cluster (mesh 1 with the input)"),
        Table("gears.cluster_small", (
            Key("teeth", 20, "mesh 2 is 100 / 20 = 5:1: the train is 3 x 5 = 15:1"),
            Key("face_width_mm", 10, "the widest face: mesh 2 carries the output torque"),
            Key("bore_diameter_mm", 8),
        ), "gear 3: the small gear of each cluster (mesh 2 with the output)"),
        Table("gears.output", (
            Key("teeth", 100),
            Key("face_width_mm", 8, "at 7 N·m plus the preload the loaded path's mesh 2 sees about 150 N: "
                "about 60 MPa Lewis root stress on 8 mm of face"),
            Key("bore_diameter_mm", 25, "on the 25 mm joint shaft"),
        ), "gear 4: the output gear of the joint"),
        Table("synthesis", (
            Key("centre_distance_mesh1_mm", 36.1, "standard (18 + 54) x 1 / 2 = 36 mm, plus 0.1 mm so that "
                "mesh 1 keeps backlash as the carriage moves"),
            Key("centre_distance_mesh2_mm", 60.0, "standard (20 + 100) x 1 / 2"),
            Key("circumferential_backlash_max_mesh1_mm", 0.13, "mesh 1 is where the preload closes the loop: "
                "it keeps backlash over the whole error budget (geargen check: 0.05 mm worst case)"),
            Key("circumferential_backlash_min_mesh1_mm", 0.10),
            Key("circumferential_backlash_max_mesh2_mm", 0.10),
            Key("circumferential_backlash_min_mesh2_mm", 0.02),
            Key("start_angle_A1_deg", -70.0, "as the robot joint: the input's lines of action near the "
                "carriage's motion"),
            Key("rounding", "whole_down"),
        ), "Where the two clusters sit so that both paths mesh (the paper's Eqs. 7-8 and Appendix). Backlash "
           "is circumferential, at the reference circles."),
        Table("errors.input", (
            Key("bearing_eccentricity_tir_um", 5, "P5 (ABEC 5) ball bearings"),
            Key("pitch_line_eccentricity_tir_um", 15, "precision-ground gears, about ISO 1328 grade 6"),
            Key("tooth_to_tooth_tir_um", 10),
        ), "The error budget (total indicator readings, here in micrometres) the carriage travel must absorb."),
        Table("errors.cluster_large", (
            Key("bearing_eccentricity_tir_um", 5),
            Key("pitch_line_eccentricity_tir_um", 20),
            Key("tooth_to_tooth_tir_um", 10),
        )),
        Table("errors.cluster_small", (
            Key("bearing_eccentricity_tir_um", 5),
            Key("pitch_line_eccentricity_tir_um", 15),
            Key("tooth_to_tooth_tir_um", 10),
        )),
        Table("errors.output", (
            Key("bearing_eccentricity_tir_um", 8, "a thin-section bearing"),
            Key("pitch_line_eccentricity_tir_um", 25),
            Key("tooth_to_tooth_tir_um", 10),
        )),
        Table("checks", (
            Key("carriage_travel_limit_mm", 0.5, "= [flexures] travel: the error budget must fit in it "
                "(geargen check: 0.12 mm worst case)"),
        )),
        Table("stiffness", (
            Key("elastic_modulus_GPa", 207, "steel gears and shafts"),
            Key("shear_modulus_GPa", 79.3),
            Key("reduce_to", "output"),
        ), "Stiffness and preload (geargen stiffness). The meshes of each path come from the gears (Eq. 1); "
           "the components below are the rest of each path."),
        Table("stiffness.components.cluster_shaft", (
            Key("kind", "shaft_torsion"),
            Key("shaft", "cluster"),
            Key("diameter_mm", 8, "the softest part of a path: 8 mm rather than 6 mm triples its stiffness"),
            Key("length_mm", 9.5, "between the two gears' mid-planes: 6 / 2 + 1.5 gap + 10 / 2"),
        ), "Each cluster's shaft twisting between its large and its small gear"),
        Table("stiffness.components.cluster_shaft_bending", (
            Key("kind", "shaft_bending"),
            Key("gear", "cluster_small"),
            Key("diameter_mm", 8),
            Key("span_mm", 20, "between the cluster shaft's two bearings"),
            Key("load_position_mm", 7, "the small gear near one bearing"),
            Key("support", "simple"),
        ), "... and bending between its bearings under the mesh-2 force"),
        Table("stiffness.components.cluster_bearings", (
            Key("kind", "linear"),
            Key("gear", "cluster_small"),
            Key("stiffness_N_per_um", 10, "a small deep-groove ball bearing with light axial preload"),
            Key("count", 2),
        ), "The cluster shaft's two bearings, along the mesh-2 line of action"),
        Table("stiffness.components.input_shaft", (
            Key("kind", "shaft_torsion"),
            Key("shaft", "input"),
            Key("diameter_mm", 5),
            Key("length_mm", 13.5, "= [parts] input_shaft_to_bevel"),
            Key("scope", "common"),
        ), "In series with both paths: the input shaft from the bevel gear ..."),
        Table("stiffness.components.output_hub", (
            Key("kind", "shaft_torsion"),
            Key("shaft", "output"),
            Key("diameter_mm", 32),
            Key("bore_diameter_mm", 25),
            Key("length_mm", 10),
            Key("scope", "common"),
        ), "... and the output gear's hub on the joint shaft"),
        Table("preload", (
            Key("max_output_torque_Nm", 7, "peak joint torque, either direction"),
            Key("line_of_action_angle_deg", 0.0, "the optimal configuration of Fig. 9"),
            Key("loop_error_budget", "mean"),
            Key("path_backlash_urad", 1141, "mesh 1's 0.10 mm at the 27 mm cluster radius, / 5, plus mesh 2's "
                "0.02 mm at the 50 mm output radius"),
        ), "The preload is set by the springs' installed length ([springs]): geargen stiffness shows about "
           "4 N·m against the 3.5 N·m (half the maximum load) the paper asks of a Type 2 drive."),
        Table("flexures", (
            Key("count", 3),
            Key("thickness_mm", 0.25, "hardened spring-steel shim"),
            Key("length_mm", 25),
            Key("width_mm", 12),
            Key("elastic_modulus_GPa", 207),
            Key("poisson_ratio", 0.29),
            Key("allowable_stress_MPa", 500, "well below the shim's yield, for long life"),
            Key("travel_mm", 0.5, "+-0.5 mm: the loop errors (0.12 mm) plus assembly adjustment; 124 MPa at the "
                "clamps"),
            Key("neutral_offset_mm", 0.0, "blades unstressed at the operating position"),
            Key("target_stiffness_N_per_mm", 7.5, "asks the design helper for blades of the same stiffness "
                "(3 x 12 E I / L^3 = 7.45 N/mm here)"),
        ), "Three parallel blades carry the motor, bevel pair and input gear (the preload carriage)."),
        Table("springs", (
            Key("count", 2),
            Key("wire_diameter_mm", 1.2, "music wire"),
            Key("mean_coil_diameter_mm", 12, "spring index 10"),
            Key("active_coils", 4, "rate G d^4 / (8 D^3 Na) = 2.97 N/mm each"),
            Key("end_type", "squared_ground"),
            Key("free_length_mm", 21.5),
            Key("installed_length_mm", 11, "10.5 mm compressed: 2 x 31 N = 62 N on the carriage, 632 MPa in "
                "the wire"),
            Key("shear_modulus_GPa", 79.3),
            Key("allowable_shear_stress_MPa", 900, "about 0.4 of the tensile strength of 1.2 mm music wire; "
                "861 MPa when compressed solid"),
        ), "Two helical compression springs push the carriage towards the output."),
        Table("layout", (
            Key("kind", "dual_pinion"),
            Key("model_tooth_thickness", "mid_tolerance", "each gear of the model made at the middle of its "
                "tooth-thickness allowance (taken from its mesh's backlash range where the mesh runs)"),
            Key("loaded_flank_gap_mm", 0.0005, "0.5 um, so that the solids do not touch"),
            Key("cluster", "separate", "large gear bonded on the small gear's shaft: two parts"),
            Key("cluster_axial_gap_mm", 1.5),
            Key("carriage_travel_mm", 0.5, "= [flexures] travel"),
            Key("upstream_stages", [[15, 30]], "the bevel pair: 15 teeth on the motor, 30 on the input shaft"),
            Key("required_ratios", [30], "motor to output 2 x 15 = 30:1"),
        ), "The assembly model (geargen build): placement, the other parts, exports."),
        Table("parts", (
            Key("bearing_clearance_mm", 0.5),
            Key("bevel_pinion_teeth", 15),
            Key("bevel_gear_teeth", 30),
            Key("bevel_module_mm", 0.8),
            Key("bevel_face_width_mm", 4, "under a third of the 13.4 mm cone distance"),
            Key("input_shaft_to_bevel_mm", 13.5, "the bevel gear's heel root circle 0.6 mm above the carriage arm"),
            Key("bevel_backlash_mm", 0.04, "circumferential at the heel pitch circles, cut as equal thinnings (about "
                "the robot joint's 0.0015 in)"),
            Key("motor_body_diameter_mm", 28, "a small servo motor with encoder"),
            Key("motor_body_length_mm", 40),
            Key("motor_flange_mm", 28),
            Key("motor_flange_thickness_mm", 3),
            Key("motor_shaft_diameter_mm", 5),
            Key("motor_shaft_length_mm", 3),
            Key("cluster_bearing_outer_diameter_mm", 22, "608 bearing, 8 x 22 x 7 mm"),
            Key("cluster_bearing_width_mm", 7),
            Key("input_bearing_outer_diameter_mm", 13, "695 bearing, 5 x 13 x 4 mm"),
            Key("input_bearing_width_mm", 4),
            Key("output_bearing_outer_diameter_mm", 37, "6805 thin-section bearing, 25 x 37 x 7 mm"),
            Key("output_bearing_width_mm", 7),
            Key("carriage_plate_thickness_mm", 3, "aluminium"),
            Key("carriage_width_mm", 24),
            Key("link_radius_mm", 68, "the cluster gears reach 61.4 mm from the symmetry line; 3.6 mm inside "
                "the walls"),
            Key("link_wall_mm", 3),
            Key("link_floor_mm", 4),
            Key("link_top_clearance_mm", 2.5),
            Key("spring_y_offset_mm", 14),
            Key("spring_model", "helix"),
        )),
        Table("export", (
            Key("stl_chordal_tolerance_mm", 0.005, "gear STL within 5 um of the exact flanks"),
            Key("stl_chordal_tolerance_parts_mm", 0.05),
            Key("stl_angular_tolerance_deg", 30),
            Key("render_view", [-60, 30]),
        )),
    ))

INCH = Starter(
    'dual_pinion',
    "a Type 2 dual-pinion drive with radial preload (Hale & Slocum 1994, Fig. 10), in inches",
    "The robot revolute joint of the paper's first case study (assemblies/robot_joint.toml): 32 diametral pitch, "
    "16/48 then 21/112, the input pinion riding on three blade flexures and pushed between two cluster gears by "
    "two springs, driven through a 15:30 bevel pair. Gear data and the synthesis and error inputs are the bold "
    "cells of the paper's Appendix; every other value is a documented choice. Change the gears first, then run "
    "geargen synth, check and stiffness again.",
    (
        Table('', (
            Key('description',
                "Robot revolute joint, dual-pinion Type 2 drive with radial-motion preload (Hale & Slocum 1994, "
                "Fig. 10)"),
            Key('length_unit', "in"),
        )),
        Table('drive', (
            Key('type', "type2"),
            Key('preload', "radial"),
        )),
        Table('gear_defaults', (
            Key('diametral_pitch_per_in', 32),
            Key('pressure_angle_deg', 20),
        )),
        Table('gears.input', (
            Key('teeth', 16),
            Key('face_width_in', 0.25),
            Key('bore_diameter_in', 0.1875),
            Key('thinning_circumferential_in', 0.000452),
        ), "Face widths are not given in the paper; chosen for a compact link (Fig. 10 is half size). Tooth "
           "thinning (circumferential, at the reference circle, split equally within a mesh) puts each mesh in "
           "the middle of the Appendix's backlash range *where it runs*: the preload carriage settles where the "
           "loop closes, so mesh 1 runs a little wider than C1 = 1.004 in. Mesh 1: 0.0045 in (range "
           "0.0040-0.0050); mesh 2 at standard centres: 0.0025 in (range 0.0008-0.0042). gear 1: input pinion on "
           "the symmetry line, on the flexure carriage"),
        Table('gears.cluster_large', (
            Key('teeth', 48),
            Key('face_width_in', 0.1875),
            Key('bore_diameter_in', 0.25),
            Key('thinning_circumferential_in', 0.000452),
        ), "gear 2: large gear of each cluster (mesh 1 with the input)"),
        Table('gears.cluster_small', (
            Key('teeth', 21),
            Key('face_width_in', 0.3125),
            Key('bore_diameter_in', 0.25),
            Key('thinning_circumferential_in', 0.00125),
        ), "gear 3: small gear of each cluster (mesh 2 with the output)"),
        Table('gears.output', (
            Key('teeth', 112),
            Key('face_width_in', 0.25),
            Key('bore_diameter_in', 1.0),
            Key('thinning_circumferential_in', 0.00125),
        ), "gear 4: output gear of the joint"),
        Table('synthesis', (
            Key('centre_distance_mesh1_in', 1.004,
                "Appendix, \"Mesh Information\" and \"Synthesis of Gear Centers\". standard 1.000 + 0.004 so mesh 1 "
                "keeps backlash"),
            Key('centre_distance_mesh2_in', 2.078125, "standard (D3 + D4)/2"),
            Key('circumferential_backlash_max_mesh1_in', 0.005,
                "Circumferential backlash at the operating centre distance, referred to the reference pitch "
                "circles (B = j_bt / cos 20deg, j_bt the gap along the line of action; each gear's free play with"
                " its mate held is B / r). Max: thinnest teeth, min: thickest."),
            Key('circumferential_backlash_min_mesh1_in', 0.004),
            Key('circumferential_backlash_max_mesh2_in', 0.0042),
            Key('circumferential_backlash_min_mesh2_in', 0.0008),
            Key('start_angle_A1_deg', -70.0, "nominal configuration to start from"),
            Key('rounding', "whole_down", "the Appendix rounds whole teeth of gear 1 down"),
        )),
        Table('errors.input', (
            Key('bearing_eccentricity_tir_in', 0.0002),
            Key('pitch_line_eccentricity_tir_in', 0.0008),
            Key('tooth_to_tooth_tir_in', 0.0005),
        ), "Appendix, \"Error Information\": TIR per gear"),
        Table('errors.cluster_large', (
            Key('bearing_eccentricity_tir_in', 0.0002),
            Key('pitch_line_eccentricity_tir_in', 0.0008),
            Key('tooth_to_tooth_tir_in', 0.0005),
        )),
        Table('errors.cluster_small', (
            Key('bearing_eccentricity_tir_in', 0.0002),
            Key('pitch_line_eccentricity_tir_in', 0.0016),
            Key('tooth_to_tooth_tir_in', 0.0005),
        )),
        Table('errors.output', (
            Key('bearing_eccentricity_tir_in', 0.0005),
            Key('pitch_line_eccentricity_tir_in', 0.0012),
            Key('tooth_to_tooth_tir_in', 0.0005),
        )),
        Table('monte_carlo', (
            Key('samples', 1000000),
            Key('seed', 1994),
            Key('model', "exact", "re-solve the geometry per sample; \"appendix\": the sheet's factors"),
            Key('error_shape', "physical", "eccentricities at random phase, tooth-to-tooth uniform"),
            Key('include_backlash_tolerance', False, "true: also draw each mesh's backlash in [min, max]"),
            Key('histogram_bins', 80),
        ), "Not in the paper: tolerance simulation of the carriage travel (geargen synth --monte-carlo)"),
        Table('stiffness', (
            Key('elastic_modulus_GPa', 207, "steel gears and shafts; Eq. 1 meshes: k = E w / 11, w = narrower face"),
            Key('shear_modulus_GPa', 79.3),
            Key('reduce_to', "output", "report path stiffnesses as torsion at the output gear"),
        ), "--------------------------------------------------------------------------------------------- "
           "Stiffness, preload and preload hardware (geargen.design.stiffness, `geargen stiffness`). The paper "
           "gives none of these numbers; each is a documented engineering choice for a small SCARA-like link "
           "(Fig. 10 is drawn at half size). Internal reference: torsion at the output."),
        Table('stiffness.components.cluster_shaft', (
            Key('kind', "shaft_torsion"),
            Key('shaft', "cluster"),
            Key('from_geometry', True),
        ), "Each cluster: the large gear is pressed and bonded onto the shaft of the small gear (paper); the 1/4 "
           "in shaft (the gears' bore) twists between the two gears' mid-planes. Its diameter and length are the "
           "placed shaft's ([parts] and the gear faces): from_geometry, never typed twice."),
        Table('stiffness.components.cluster_support', (
            Key('kind', "shaft_support"),
            Key('gear', "cluster_small"),
            Key('stiffness_N_per_um', 10),
            Key('from_geometry', True),
        ), "... and the small gear is carried by that shaft on two small deep-groove ball bearings (1/4 in bore, "
           "light axial preload, about 10 N/um radial each): the shaft bending between them and the bearings "
           "through their levers, at the bearings and the gear as built (bearing_clearance and widths in [parts];"
           " geargen.core.stiffness.supported_shaft_compliance)."),
        Table('stiffness.components.input_shaft', (
            Key('kind', "shaft_torsion"),
            Key('shaft', "input"),
            Key('scope', "common"),
            Key('from_geometry', True),
        ), "Shared by both paths, in series with the drive: the input pinion's 3/16 in shaft up to the bevel gear"
           " (input_shaft_to_bevel in [parts]), and the output gear's hub on the joint shaft (the hub is not a "
           "modelled part: its length is given here)."),
        Table('stiffness.components.output_hub', (
            Key('kind', "shaft_torsion"),
            Key('shaft', "output"),
            Key('diameter_in', 1.25),
            Key('bore_diameter_in', 1.0),
            Key('length_in', 0.4),
            Key('scope', "common"),
        )),
        Table('duty', (
            Key('material', "case_carburised",
                "The load spectrum defaults to [preload] max_output_torque both ways for the whole life (60 rpm, "
                "20,000 h): the conservative rating of a drive whose duty is not yet known. Every mesh carries "
                "its preload all its life, so the gears are case carburised (ISO 6336-5 MQ): through hardened at "
                "300 HV they fall below S_H 1 (geargen check names this fix when the material is left out)."),
            Key('quality', "MQ"),
        )),
        Table('preload', (
            Key('max_output_torque_Nm', 5.0, "peak joint torque of the link (either direction)"),
            Key('line_of_action_angle_deg', 0.0,
                "The preload itself is set by the springs' installed length (see [springs]); the paper asks for "
                "at least half the maximum load in a type 2 drive. the optimal configuration of Fig. 9 "
                "(synthesis: within 0.11 deg)"),
            Key('loop_error_carriage_travel_in', 0.0095,
                "Loop error when the synthesis budget is not available: the Appendix's (Sum + RSS)/2 carriage "
                "travel."),
            Key('loop_error_budget', "mean", "which synthesis budget the headline uses: \"mean\", \"sum\" or \"rss\""),
            Key('path_backlash_urad', 1457,
                "Flank clearance of one path at the output, for the preload diagram: minimum backlash of mesh 1 "
                "(0.0040 in at the 0.75 in cluster pitch radius, / R2 = 5.333) plus mesh 2 (0.0008 in at 1.75 "
                "in)."),
        )),
        Table('flexures', (
            Key('count', 3),
            Key('thickness_in', 0.01),
            Key('length_in', 1.0),
            Key('width_in', 0.5),
            Key('elastic_modulus_GPa', 207),
            Key('poisson_ratio', 0.29),
            Key('allowable_stress_MPa', 500, "hardened 1095 shim, well below yield for long life"),
            Key('travel_in', 0.02, "+-0.020 in from neutral: loop errors plus assembly adjustment"),
            Key('neutral_offset_in', 0.0, "blades unstressed at the nominal operating position"),
            Key('target_stiffness_N_per_mm', 8, "ask the design helper for the shortest blades of this stiffness"),
        ), "Three parallel blade flexures carry motor, bevel pair and input gear (Fig. 10): 0.010 in hardened "
           "spring-steel shim, 1/2 in wide, 1 in free between clamps."),
        Table('springs', (
            Key('count', 2),
            Key('wire_diameter_in', 0.045),
            Key('mean_coil_diameter_in', 0.45),
            Key('active_coils', 4),
            Key('end_type', "squared_ground"),
            Key('free_length_in', 0.8),
            Key('installed_length_in', 0.35, "sets the preload: 2 x 2.83 N/mm x 11.4 mm = 64.8 N on the carriage"),
            Key('shear_modulus_GPa', 79.3),
            Key('allowable_shear_stress_MPa', 900, "about 0.4 of the 2170 MPa tensile strength of 0.045 in music wire"),
        ), "Two helical compression springs push the carriage (Fig. 10): music wire, squared and ground."),
        Table('train', (
            Key('material', "steel", "every gear and shaft of the joint"),
            Key('mesh_friction_coefficient', 0.05, "oiled, hardened steel flanks"),
            Key('allowed_lost_motion_arcsec', 60, "the link's tip may not wander more than 0.3 mm at 1 m"),
            Key('motor_rotor_inertia_kg_cm2', 0.03),
            Key('motor_torque_constant_Nm_per_A', 0.035),
            Key('motor_peak_torque_Nm', 0.4),
            Key('load_inertia_kg_m2', 0.02, "the link and its payload about the joint axis"),
            Key('bandwidth_Hz', 15, "position loop of the geared joint"),
            Key('damping_ratio', 0.7),
            Key('upstream_backlash_arcmin', [11],
                "the bevel pair 15:30 (32 DP, the [parts] bevel keys): 0.0015 in circumferential backlash at the "
                "30-tooth gear's 0.469 in pitch radius (the fine-pitch allowance of AGMA 2002) = 11 arcmin at the"
                " input shaft. Its stiffness is Eq. 1 on the pair's face (no value here)."),
        ), "--------------------------------------------------------------------------------------------- The "
           "drive as its servo sees it (`geargen train`). Not in the paper: a small brushless servo with encoder "
           "for a SCARA-like link; the link's inertia about the joint dominates, as the paper's R^2 argument "
           "assumes (0.02 kg m^2 / 32^2 = 2.0e-5 kg m^2 at the motor against a 3.0e-6 rotor)."),
        Table('layout', (
            Key('kind', "dual_pinion", "gears placed by the centre synthesis of [synthesis]"),
            Key('model_tooth_thickness', "as_designed", "the teeth as the [gears.*] tables give them (thinning included)"),
            Key('loaded_flank_gap_in', 2e-05, "0.5 um left on the working flanks so the solids do not touch"),
            Key('cluster', "separate", "large gear pressed and bonded on the small gear's shaft with a jig"),
            Key('cluster_axial_gap_in', 0.0625,
                "(paper): two parts, the same angular orientation in both clusters. spacer between a cluster's "
                "large and small gear"),
            Key('carriage_travel_in', 0.02, "+- carriage travel drawn in the layout (= [flexures] travel)"),
            Key('upstream_stages', [[15, 30]], "bevel pinion 15 T on the motor, bevel gear 30 T on the input shaft"),
            Key('required_ratios', [32], "the re-design doubled the joint's ratio: motor to output 32:1"),
        ), "--------------------------------------------------------------------------------------------- "
           "Assembly model (`geargen build`): gear placement, the non-gear parts as simple solids, exports. The "
           "paper gives none of these sizes; each is a documented choice for the link of Fig. 10 (drawn at half "
           "size), in inches like the rest of the file."),
        Table('parts', (
            Key('bearing_clearance_in', 0.02, "axial gap between a bearing and the gear face next to it"),
            Key('bevel_pinion_teeth', 15, "on the motor shaft"),
            Key('bevel_gear_teeth', 30, "on the input shaft (2:1)"),
            Key('bevel_diametral_pitch_per_in', 32),
            Key('bevel_face_width_in', 0.15),
            Key('input_shaft_to_bevel_in', 0.525,
                "input gear mid-plane to the bevel gear's heel pitch circle (also the twisting length of "
                "[stiffness] input_shaft); 0.50 put the toothed gear's heel root circle 5 um into the carriage "
                "arm: raised for a bearing_clearance under it"),
            Key('motor_body_diameter_in', 1.0, "servo motor with encoder, envelope"),
            Key('motor_body_length_in', 1.5),
            Key('motor_flange_in', 1.0, "square mounting flange"),
            Key('motor_flange_thickness_in', 0.125),
            Key('motor_shaft_diameter_in', 0.1875),
            Key('motor_shaft_length_in', 0.1, "shaft stub from the flange to the bevel pinion's heel"),
            Key('cluster_bearing_outer_diameter_in', 0.625, "R4 deep-groove ball bearing, 1/4 x 5/8 x 0.196 in"),
            Key('cluster_bearing_width_in', 0.196),
            Key('input_bearing_outer_diameter_in', 0.5, "R3, 3/16 x 1/2 x 0.196 in"),
            Key('input_bearing_width_in', 0.196),
            Key('output_bearing_outer_diameter_in', 1.5, "thin-section bearing, 1 x 1.5 x 0.25 in"),
            Key('output_bearing_width_in', 0.25),
            Key('carriage_plate_thickness_in', 0.125, "aluminium plate, post, arm and spring wall of the carriage"),
            Key('carriage_width_in', 0.9),
            Key('link_radius_in', 2.0, "round end of the link about the joint axis"),
            Key('link_wall_in', 0.12),
            Key('link_floor_in', 0.15),
            Key('link_top_clearance_in', 0.1, "walls reach this far above the highest part"),
            Key('spring_y_offset_in', 0.55, "the two springs sit at y = +-0.55 in either side of the symmetry line"),
            Key('spring_model', "helix", "swept wire (\"envelope\": a tube)"),
        )),
        Table('export', (
            Key('stl_chordal_tolerance_mm', 0.005, "gear STL within 5 um of the exact flanks (mesh checks on meshes)"),
            Key('stl_chordal_tolerance_parts_mm', 0.05, "the other parts' STL within 50 um (review only)"),
            Key('stl_angular_tolerance_deg', 30),
            Key('render_view', [-60, 30], "azimuth, elevation of the rendered view (deg)"),
        )),
    ),
    units="in",
)

#: the kind's starters by length unit
STARTERS = {"mm": METRIC, "in": INCH}

__all__ = ["METRIC", "INCH", "STARTERS"]

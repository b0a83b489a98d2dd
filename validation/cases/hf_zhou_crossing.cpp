// Hydraulic fracture validation 5: a hydraulic fracture meets a pre-existing fracture, the ten
// tri-axial tests of Zhou et al. (2008) as the thesis tabulates them (003_a918a6800360952d.txt,
// Table 4.2; ../shared/reference/zhou2008_crossing_tests.csv). A 2D horizontal section through
// the borehole of the 300 mm cement/sand block (plane strain, sigma_v out of plane; E = 8.402 GPa,
// nu = 0.23 from zhou2008_block_properties.csv), LPS rock, a 3 mm borehole with a 24 mm pre-crack
// along sigma_H (the perforation's direction), fluid injected at 3e-9 m^3/s into the 1 mm slab,
// in-situ stresses sigma_H along x and sigma_h along y brought to equilibrium first, then dynamic
// relaxation load steps. The pre-existing fracture is an interface through (75 mm, 0) at the test's
// approach angle to the fracture's path, clipped a few spacings inside the block: tensile strength
// 1 MPa, no cohesion, friction 0.89 (Zhou's direct shear tests). One parameter set for every row:
// the calibration is the rock's tensile strength T = 3 MPa (a cement mortar's, about a tenth of its
// 28 MPa unconfined compressive strength), on which the rock's bonds break: bond_failure =
// "normal_stress" (pd/normal_stress_failure.hpp; a crack then grows at K = 0.87 T sqrt(delta), 0.25
// MPa m^0.5 at 3 mm spacing, 0.20 at 2 mm). A stretch criterion is at odds with S-1 (15 / 0
// MPa): its plane strain Poisson stretch, 5.0e-4, exceeds the s00 = 3.5e-4 (T0 about 3.1 MPa) of
// the stretch calibration before, with no tensile stress anywhere, and the block broke throughout in
// the first load step (the thesis' alpha = 0.1 lifts the limit to 5.2e-4 only; alpha = 0.25 kept it
// whole but arrested 2-1). Contact at one spacing ([contact] distance = 1): the dry pre-crack's
// faces, pressed by sigma_h, stay at their reference distance. Without contact they closed by a
// tenth of a spacing (nothing but the cut families held them), their bonds stretched past any limit
// and the face rows broke loose; the fluid then pushed the loose particles apart at no
// pressure (2-1 at 3 mm: 10 kPa, no growth, where with contact it holds 6.5-7.4 MPa and the
// fracture grows). Bonds break only at each load step's equilibrium (solver breaking =
// "at_equilibrium", 40 load steps over 4 s of injection): breaking in the relaxation's iterations
// let transients run S-1's tips to the block's faces at t = 1.05 s. The interface reads dilated
// only with the fluid above the compression sigma_n the in-situ stresses put across it
// (geomech/interface_outcome.hpp, the thesis' EQ 4.7).
// The fluid is Zhou's guar (135 mPa s; the thesis, section 4.3.2), flowing along the cracks by the
// cubic law (hf/viscous_fluid.hpp, validated by hf_kgd_viscosity): for this scene's injection (3e-6
// m^2/s per unit height) the KGD fracture's dimensionless toughness K' / (E'^3 mu' Q)^(1/4) is 0.6,
// viscosity-dominated, its inlet net pressure 0.545 (mu' E'^2 / t)^(1/3) (Adachi and Detournay 2002)
// 2.2 MPa when the fracture reaches the interface (t = 2 s). What the experiment asks of it
// (Warpinski and Teufel; the thesis' EQ 4.8): the interface dilates where the net pressure
// p - sigma_h at the junction exceeds (sigma_H - sigma_h) sin^2(theta), 2.25 / 1.25 / 0.75 MPa for
// the dilated 2-8 / 2-3 / 2-5 (1.5 for S-2, which the thesis read dilated) and 2.5 MPa for the
// arrested 2-7. A lumped, inviscid fluid holds only K / sqrt(pi a) of the free wing, 0.4 to 0.9
// MPa here, and a K that gave more stops 2-1 and 2-2 crossing (Renshaw and Pollard 1995: T = 13.5
// MPa would be needed, and sigma_H / (T + sigma_h) = 10 / 18.5 is under their 0.70).
// The in-situ stresses come through rigid platens ([in_situ_stress] faces = "platens",
// pd/platens.hpp): Zhou et al. loaded the blocks through the steel plates of a true tri-axial
// frame, Teflon and Vaseline against shear (the thesis, section 4.3.2), so each face stays flat and
// the block cannot turn where a fracture opens under a face.
// Measured at 3 mm with the guar and the platens (rift run on each row's scene, one thread, 4-21
// min a row; p the borehole's pressure; 2026-11-24): 8 of 9 as the experiment. 2-1 crossed (36 mm
// past the plane at t = 4 s), 2-2 crossed (39 mm), 2-4 crossed (20.8 mm at t = 4 s, where crossing
// counts from 18.1 mm: the closest row), 2-6 crossed (33.5 mm past at t = 4 s; both wings
// straight), S-1 crossed (89 mm when the fluid broke through at t = 1.4 s), 2-5 dilated (from t =
// 2.3 s, p = 6.83 MPa; open and wet along 51 mm), 2-3 dilated (from t = 2.5 s, p = 6.76 MPa >
// sigma_n = 6.25 MPa; 45.6 mm), 2-7 arrested (2.6 mm past; its interface slipped and opened along
// 18.8 mm at t = 0.8 s with the borehole at 5.56 MPa, the interface's fluid under sigma_n = 5.5
// MPa); S-2 (no experiment) dilated as the thesis (39.2 mm). Not yet: 2-8 crossed (25.6 mm past at
// t = 4 s, from t = 3.5 s; the experiment dilated, the thesis crossed+dilated): the fracture
// arrives at t = 2.1 s with p = 6.88 MPa, under sigma_n = 7.25 MPa, and its interface never fails:
// the tip's stress, smoothed over a horizon in the interface law (the rock stress from the bulk
// strain), does not slip it under 7.25 MPa of compression, so the far side's rock breaks first.
// With T = 4 MPa it crossed as well (20.8 mm past at t = 4 s, p = 7.01 MPa on arrival). Renshaw and
// Pollard's ratio sigma_H / (T + sigma_h) is 1.0 for 2-8, the lowest of the crossing candidates
// (2-1: 1.25), so the row sits at the criterion's edge.
// Tried for 2-8 on 2026-11-25 (3 mm, platens; none kept): the interface's tensile strength 0
// instead of 1 MPa (a cohesionless sheet): crossed, 20 mm past at t = 3.7 s, no interface bond
// failed (the normal stress across the plane at the junction stays 7.1-8.0 MPa of compression as
// the tip arrives: the pressurized fracture's T-stress is compressive along its path); 2-4
// unchanged (20.8 mm). The fracture's fluid against the interface at the junction (the interface
// bonds of fracture faces within a spacing of the plane taking its pressure off their normal
// stress, Warpinski and Teufel with the fluid at the junction): with the local pressure of the
// viscous fluid there (0.09 MPa as the tip arrives, 2.6-5.0 MPa a load step later) nothing slipped
// and 2-8 crossed (27.5 mm), 2-4 crossed (28.6 mm); with the borehole's pressure both slipped along
// the interface from t = 1.8 s and the crossing slowed alike in both (2-8 9 mm at t = 3.1 s, 2-4
// 17.8 mm at t = 3.8 s, under its 18.1 mm threshold): the rule cannot tell them apart, as the
// thresholds say (2-8 slips above 0.79 MPa of net pressure at the junction, 2-4 above 1.85, and
// both arrive with about 1.9 at the borehole).
// Re-run at 3 mm after the passes went to runs of bonds (2026-11-25/26), one thread each: every row
// as before. 2-1 crossed 36 mm, 2-2 39 mm, 2-4 19.7 mm (was 20.8), 2-6 33.5 mm, S-1 crossed (the fluid
// broke through at t = 1.4 s, 89 mm past), 2-5 dilated (51 mm), 2-3 dilated (44.3 mm), 2-7 arrested
// (2.6 mm; open along 18.8 mm), S-2 dilated (42.4 mm; broken rock 10.6 mm past), 2-8 crossed (25.6 mm).
// Tried for 2-8 on 2026-11-26 (not kept): the interface law on the strain of each end's bonds within
// half a horizon (1.5 spacings) instead of its whole family, to read more of the tip's field: 2-8
// crossed still (11.9 mm past at t = 3.4 s, its interface never failed) and 2-4 crossed further
// (24.5 mm). The linear-elastic reading of the table (Renshaw and Pollard 1995, Gu and Weng 2010:
// the tip at the interface, its field at r_c of amplitude sigma_h + T0, where the far side's rock
// fails, on top of the far field; crossing where the interface does not slip there, friction 0.89):
// the 90-degree rows cross and the 30- and 45-degree rows slip for every T0; at 60 degrees 2-8
// (sigma_h = 5 MPa) slips for T0 >= 0.5 MPa but 2-4 (sigma_h = 3) only for T0 >= 1.6 (2-6 2.3, S-1
// never), so the table's crossings follow for 0.5 <= T0 <= 1.5 MPa (0.9 to 2.0 with the pressurized
// fracture's T-stress, -2 MPa along its path). It separates 2-8 from 2-4 by sigma_h alone, with a
// far-side strength a third to a half of the T = 3 MPa the rock needs elsewhere (with 3 MPa it
// stops 2-4 and 2-6 too): a model that crosses 2-8 reads less of the tip's field at the interface
// than that, and one that reads all of it stops 2-4 unless its far side breaks at about 1 MPa.
// What the table itself suggests (2026-11-25, not yet tried): every row's outcome follows from the
// fluid reaching the interface at about the borehole's breakdown pressure, p_b = 3 sigma_h - sigma_H
// + T (Hubbert and Willis; no less than sigma_h), read against the thesis' EQ 4.7 (dilated where p_b
// > sigma_n): with T = 3 MPa, 2-8 p_b = 10 > sigma_n = 7.25 (dilated), S-2 10 > 6.5, 2-3 8 > 6.25,
// 2-5 10 > 5.75 (dilated); 2-1 8 < 10, 2-2, 2-4, 2-6, S-1 about sigma_h, far below their 8.25-11.25
// (crossed); 2-7 about 3 < 5.5 at 30 degrees (arrested): ten of ten, the thesis' row S-2 too. In the
// laboratory the fracture breaks down from the bare hole and runs on the fluid the injection line
// stored at p_b. This scene's 24 mm pre-crack takes that peak away (the fracture starts at sigma_h +
// K_Ic / sqrt(pi a), 6.3 MPa in 2-8, and arrives at 6.88). So the next try: a short notch instead of
// the pre-crack (the in-situ stage keeps the wall whole; S-1's wall is in 15 MPa of hoop tension
// there) and the injection system's compliance (a lumped volume of fluid at the borehole's pressure),
// one value for every row, with the breakdown case (hf_breakdown) as its check.
// Tried on 2026-11-26 (3 mm, rift run on the row's scene, not kept): that lead, as the borehole's
// `breakdown_pressure` (the pre-crack shut to the fluid until the borehole reaches Hubbert and
// Willis' p_b with T = 3 MPa) and `injection_system_volume` V_s = 1e-5 m^3 (over 20 s, 200 load steps:
// the pump fills V_s at 3e-9 m^3/s). 2-8 (p_b = 10 MPa): the wall broke down at t = 15.2 s, the
// fracture ran to the interface in that load step (43 breaking passes, p 10 -> 8.47 MPa), and the
// interface dilated at t = 15.3 s (p = 7.91 > sigma_n = 7.25 MPa, open along 38.9 mm; for the
// first time in this row), but the far side's rock, broken 2.6 mm past the plane as the tip arrived,
// grew on with the fluid: crossed from t = 15.6 s (18.2 mm past, p = 7.17 MPa), 31 mm at t = 15.9 s.
// Crossed+dilated, the thesis' outcome, not the experiment's. With V_s = 3e-5 m^3 (50 s, 500 load
// steps) the same sooner: dilated at once (47 mm open), 40 mm past the plane a load step later.
// 2-1 (p_b = 8 MPa) crossed as before (39 mm past at t = 14.7 s, its interface never wet). So the
// breakdown pressure lets the fluid reach the interface above sigma_n, but the tip that reaches it
// breaks the far side in the same breaking passes before the interface takes the fluid: the
// junction itself (which side of the interface breaks first under the arriving tip) still decides.
// Also tried (the same 2-8 scene): at each equilibrium the interface law alone first, the rock's
// bonds only at an equilibrium where no interface bond failed (the interface, the weaker plane,
// answering first). The same: dilated at t = 15.3 s (3.1 mm of broken rock past the plane), and the
// far side's crack grew on, 11.9 mm past at t = 15.4 s with p = 7.59 MPa. So it is not that both
// break in one pass: the far side's first spacing of rock breaks under the arriving tip (its
// horizon, 9 mm, reaches across the plane) and, wet and under sigma_h = 5 MPa only, takes the fluid
// the interface (sigma_n = 7.25 MPa) gives up as the pressure falls. What might: a finer horizon at
// the junction, or the interface's fluid taken as the tip's (blunting) load.
// Tried on 2026-11-29 (3 mm, platens, one thread a row; not kept): the interface law reading the
// bond's own stretch for the strain along the bond, as the rock's bonds do (normal_stress_failure.hpp):
// the traction on the plane from the mean strain of the ends with its component along the bond
// replaced by the bond's stretch, so that the law sees the arriving tip's opening as sharply as the
// far side's rock bonds do. 2-8 crossed still (20.4 mm past at t = 3.9 s, its interface never
// failed; 8.0 mm at t = 3 s), and 2-4 crossed only just (18.2 mm at t = 4 s, where crossing counts
// from 18.1 mm; 13 mm at t = 3.7 s). So it slowed both crossings alike and did not tell them apart.
// Tried on 2026-11-29 (twelfth session; 3 mm, platens, one thread; not kept): the strengths from
// the linear-elastic field on the fracture's line ahead of its tip, where sigma_xx and sigma_yy
// rise alike (Westergaard's solution for any load on the faces): the far side's rock breaks once
// the rise reaches sigma_h + T, the interface opens once it reaches sigma_n + T_i, so the interface
// answers first where (sigma_H - sigma_h) sin^2(theta) < T - T_i: 2.25 MPa for 2-8, 5.25 for 2-4,
// 5 for 2-1, more for 2-2, 2-6 and S-1; T - T_i between 2.25 and 5 would give the table. With this
// scene's T = 3, T_i = 1 (T - T_i = 2) 2-8 sits just outside. 2-8 with T = 5 MPa, T_i = 0: the
// interface never opened (0 mm) and the far side broke from t = 2.7 s (p = 6.96 MPa; 16.9 mm past
// at t = 4 s, read arrested under the 18.1 mm threshold); with T = 6, T_i = 1: crossed (22.5 mm,
// p = 6.64 MPa at t = 4 s), and with T = 6, T_i = 0 crossed as well (21.2 mm at t = 3.9 s), its
// interface never open either. The bond-pair stress (the stress output) of the base scene at t =
// 2.0 s, on the fracture's line a spacing ahead of its tip (x = 71.8 mm): sigma_yy up 7.1 MPa from
// the far field, sigma_xx up 4.2 (0.59 of it, where the linear-elastic field has them equal), and
// the normal compression across the interface at the junction 3.2-3.9 MPa by that stress. The
// interface law reads its stress from the correspondence strain of intact bonds (rock_stress in
// geomech/interface_law.hpp, chosen because the bond-pair stress lost a third of the compression beside a
// fracture at a 90-degree interface), which stays at 7.1-8.0 MPa there (above): this model's
// interface does not see the tip's rise in sigma_xx that the far side's rock sees in sigma_yy, and no
// pair of strengths reaches it. A measure of the interface's stress that reads the tip's field as
// the rock's bonds do, and keeps the 90-degree rows whole, is what 2-8 still asks for.
// Traced on 2026-11-29 (thirteenth session; the interface law's state within 12 mm of the junction
// printed every 300 force evaluations, not kept): that measure is not what lets 2-8 cross. In 2-8 the
// law slips its bonds at the junction (|tau| / (mu sigma_n) 1.03 at (73.5, 0) mm) with the tip at 66
// mm, and parts them (2.9 MPa of tension against T_i = 1) with the tip at 69 mm, while the far side's
// rock bonds read -0.5 MPa (compression) at the first slip and 2.5 MPa at the parting, against T = 3;
// 2-4 slips at its junction likewise (1.04, tip at 63 mm; far side 0.4 MPa). The failed patch stays a few spacings long (the slip ratio 0.58-0.65 at
// 4.5 mm along the plane), and once the tip is at the plane the far side's rock 1.5 mm past it reads
// 4.2 MPa (2-8) and 3.1 (2-4) and breaks: the bonds across the plane outside the patch, up to a
// horizon long, carry the near side's opening over to the far side. So both rows blunt first and
// cross anyway, where Renshaw and Pollard's slip stops the crossing. The law on either end's stress
// alone (a bond failing where the rock on one face exceeds it, rather than on the mean of both):
// 2-4 arrested (15.4 mm past at t = 4 s, under its 18.1 mm threshold; the far side broke more slowly)
// and 2-8 still crossing (10 mm past at t = 3.0 s and growing). The law at sites of the plane (each
// bond read the stress of the two interface particles nearest its crossing point, one each side, so
// that every bond crossing the plane at a failed spot fails, long bonds too): 2-8 crossed still
// (17.1 mm past at t = 3.5 s and growing) and 2-4 crossed further (29.4 mm at t = 3.7 s).
// What the failed bonds at 2-8's junction do (same trace, bonds with an end within 6 mm of it, t =
// 2.2-2.4 s): 175 have failed; 45-55 have their faces apart and 120-130 are pressed together, of
// which about 60% are at the Coulomb cap (geomech/interface_contact.hpp) and the rest stick; together the
// pressed ones carry 0.28-0.46 of their normal force in shear, against mu = 0.89. Under dynamic
// relaxation their slip is held at zero (compute_forces' history_dt is 0), so a failed bond's
// friction is its elastic tangential force capped at mu times its normal one. So the blunting the
// slip should bring is partial: most of the failed patch is shut and much of it still sticks. The
// next trace: the forces on the far side's rock 1.5 mm past the plane (76.5, 1.5) mm, split into the
// intact bonds across the plane, the failed bonds' contact and the fluid on the faces.
// Tried on 2026-11-30 (fourteenth session; 3 mm, platens, one thread; not kept): the pore pressure's
// shift (hf/wet_rock.hpp) kept to the near side, a bond on the far side of the interface
// not counted as crossing the near side's crack patches (the wet tip's process zone stopping at the
// plane; the far side's own patches, once it breaks on the total stress, count as before): 2-8
// crossed still (0.2 mm past at t = 2.1 s, 24.9 mm at t = 3.9 s) and 2-4 fell under its threshold
// (18.0 mm at t = 4 s): the far side's first bonds break on the total stress. The failed bonds'
// contact without friction (the law still failing them at mu = 0.89): 2-8 10.4 mm past at t = 4 s
// (arrested, p = 6.52 MPa, never over sigma_n) and 2-4 17.0 mm (under 18.1): the failed bonds'
// friction carries much of the near side's opening to the far side, in both rows alike. Every try
// so far has slowed the two crossings together. The failed bonds' tangential spring on the slip
// across the plane, (delta - eps xi)_t with eps the ends' mean rock strain (as interface_opening takes
// the normal opening), instead of the whole tangential jump since the reference: 2-8 crossed (27.5 mm
// past at t = 4 s) and 2-4 crossed further (34.6 mm): not kept.
// Run on past t = 4 s (2026-11-30, fifteenth session; the same scenes to t = 6 s in 60 load steps,
// the failed bonds' contact frictionless; not kept): 2-8 crossed at t = 4.9 s (18.7 mm past) and
// ran on to 24.9 mm at t = 5.4 s, its borehole falling from 6.88 to 6.25 MPa and never over sigma_n
// = 7.25; 2-4 crossed at t = 4.2 s. So the frictionless contact only slows both, and 2-8's
// pressure, falling as its fracture lengthens, cannot reach sigma_n after the tip arrives. Renshaw
// and Pollard's test is decided at r_c, within the tip's process zone, by a slip zone that need not
// be longer than that; here the far side's rock breaks on the stretch of bonds a horizon long (9 mm
// at 3 mm, 6 mm at 2 mm: both miss 2-8 alike), longer than the slipped patch (a few spacings), so
// the intact bonds beyond it carry the tip's opening across. A horizon smaller than that patch at
// the junction (a local refinement, e.g. a dual-horizon model, Ren et al. 2016) is what this reading
// asks for next.
// A first check of that reading (2026-11-30, sixteenth session; 3 mm, platens, one thread; not
// kept): the horizon at 2.015 spacings (6 mm) instead of 3.015, so that the few spacings of slipped
// patch are longer against it. 2-8 crossed sooner (from t = 2.9 s, 12.6 mm past the plane where
// crossing then counts from 12.1 mm; 29 mm at t = 4 s, its interface never wet) and 2-4 later (from
// t = 3.6 s; 16.7 mm at t = 4 s). The shorter horizon held 2-4 back and not 2-8, the order the
// experiment has the other way round. So a horizon shorter against the spacing does not separate
// them; if the patch is a few spacings at any spacing, a dual-horizon refinement at fixed ratio may
// not either, and the reading above stays untested at the junction's own resolution.
// The far side beside the dilated interface (2026-11-30, seventeenth session; the breakdown-pressure
// scene of 2026-11-26 again, V_s = 1e-5 m^3, its stress field written; not kept). The estimate to
// check: on the faces of an open interface holding fluid at p the normal stress is -p and the
// stress along it -(sigma_t + p - sigma_n), so sigma_yy there is about -6.8 MPa at p = 7.92 MPa and
// a wet flaw on the far side has about 1.1 MPa of net opening, against 2.9 in the far field. At t =
// 15.3 s (dilated, 2.6 mm of broken rock past the plane) the bond-pair stress (the rock's part,
// without the fluid's) of the wet far-side particles 2-6 mm past the plane reads sigma_yy = +0.7 to
// +1.3 MPa, a total of about -6.9: the model reads the estimate there. But the dry rock ahead, 7-10
// mm past, reads a total sigma_yy of -0.2 to -1.5 MPa, and the ligament 25-30 mm past -3.1 to -3.4,
// not sigma_h = 5: with 150 mm of the 300 mm section cut by a crack at 7.9 MPa the rest must carry
// (-5 x 300 + 7.9 x 150) / 150 = -2.1 MPa on average (the platens hold the total force). The far
// side's first spacing of broken rock, wet, grows into that (K = 1.12 (p + sigma_yy) sqrt(pi a)
// passes 0.25 MPa m^0.5 at a = 0.7 mm with sigma_yy = -3), and it did (8.3 mm past at t = 15.4 s).
// A 2D section through the borehole makes the fracture as tall as the block, so the ligament's
// tension is what a plane-strain section asks for; a penny-shaped fracture of the same radius in the
// 3D block would cut a fifth of the section, not half (a 2D section about 760 mm wide gives its
// ligament the same mean stress). But that is not what lets 2-8 cross: the base scene (no
// breakdown pressure) in a 600 mm block (the interface through (75 mm, 0) as before, extended to the
// new faces; one thread, to t = 2.5 s) broke its far side as soon: 3.3 mm past the plane at t = 2.3
// s and 5.4 mm at t = 2.5 s with p = 6.96 MPa, under sigma_n (the 300 mm block: 3.1 and 3.9 mm,
// 6.81 MPa), its interface never wet, with the ligament 45-75 mm past the plane at -4.4 to -4.6
// MPa, near sigma_h. The far side breaks in the arriving tip's own field, 9-15 mm past the plane
// (sigma_yy -2.7 to -3.7 MPa there), before the section's equilibrium matters.
// The injection rate (2026-11-30, nineteenth session; not kept). This scene's 3e-9 m^3/s into the
// 1 mm slab is not the laboratory's: the thesis gives 4.2e-9 m^3/min (7e-11 m^3/s into the 3D
// block; zhou2008_block_properties.csv), a 2D rate of 7e-12 m^3/s into 1 mm if the fracture were
// 10 mm tall (the open hole), less if taller. With it the guar's KGD toughness number is about 2.7
// (toughness-dominated; 0.6 here). 2-8 at 3 mm with 7e-12 m^3/s and the injection time stretched
// alike (1720 s in 40 load steps; one thread, 9 min 44 s): arrested, broken rock 10.8 mm past the
// plane (under the 18.1 mm threshold), its interface never open or wet, when the fluid broke
// through to the block's outer surface at t = 1161 s. Dilated, as the experiment, still not; 2-4
// at that rate not yet run.
// The far side's own strain (2026-12-01, twentieth session; 3 mm, platens, guar, one thread; not
// kept): the rock's failure strain of each particle (update_failure_strain, bulk_strain.hpp) from
// its bonds that do not cross the interface, so that a far-side particle no longer reads the near
// side's opening through the intact interface bonds of its 9 mm horizon. 2-8 crossed as before
// (from t = 3.5 s: 18.4 mm past, 19.7 mm at 3.6 s; its interface never open) and 2-4 too (23.2 mm
// at t = 4 s): the far side does not break on what its strain reads across the plane.
// The breakdown-pressure scene in a section twice as long along the fracture (2026-12-01,
// twenty-first session; x from -300 to 300 mm, the block 300 mm across sigma_h as before, so that
// the far side's ligament keeps near sigma_h; p_b = 10 MPa, V_s = 1e-5 m^3, 20 s in 200 load steps;
// one thread, 14 min to t = 16.3 s; not kept): the same as in the 300 mm block. The wall broke
// down at t = 15.2 s, the interface dilated at t = 15.4 s (p = 8.06 MPa, open along 32.9 mm; broken
// rock 3.1 mm past the plane), and the far side's crack grew on with the fluid, crossed from t =
// 15.8 s (19.5 mm past, p = 7.54 MPa) and 35.3 mm at t = 16.3 s. So once a spacing of the far
// side's rock is broken and wet it runs as the hydraulic fracture itself does, at sigma_h plus
// K / sqrt(pi a) (about 7 MPa here, under the 7.25 MPa plus T_i the interface asks for), whatever
// the section's length; only the far side's first break decides.
// With traction faces instead (the same scenes, faces = "tractions"): 7 of 9. 2-6 arrested (13.7 mm
// past the plane at t = 4 s; both wings turned toward +y some 80 mm out, as in 2-4, under the 13 /
// 3 MPa that should keep them straight: the free faces let the block bend), 2-8 crossed (22.3 mm);
// 2-1 30 mm, 2-2 33 mm, 2-4 30.7 mm, S-1 46.7 mm, 2-7 arrested (p 3.97 MPa), 2-5, 2-3 and S-2
// dilated. The borehole's net pressure runs at 0.7-0.8 of the unbounded KGD's (2-8: 2.12 MPa at t =
// 1 s against 2.75), falling with the fracture's length.
// The fluid's way through the junction (2026-11-24). A bond across the interface that broke as rock
// (the fracture crossing it) was read by the flow as a shut interface contact, with no opening: the
// far side's crack stayed dry, without the fluid's pressure on its faces or in its rock, and the
// fracture stopped a spacing past the plane (2-1 at 2 mm, and at 3 mm with the lattice moved half a
// spacing). At 3 mm the 90-degree interfaces ran through a column of lattice sites, which were on
// neither side of the line, so their rock bonds bridged the interface and 2-1 and 2-2 crossed
// through that column. Both fixed (hf/network_flow.hpp, geometry/precrack.cpp: a site on the line
// counts with one side); failed interface bonds across the fluid's crack carry no contact
// (hf/crack_junction.hpp). Before (traction faces): 7 of 9 at 3 mm as well, 2-8 arrested 17.1 mm past the plane and
// 2-6 8.5 mm.
// At 2 mm (the second horizon, 12-62 min a row) with the platens (2026-11-24/25, rows run so far):
// 2-1 crossed (41 mm past the plane at t = 4 s), 2-4 crossed (28.9 mm at t = 3.6 s), 2-6 crossed
// (20 mm past at t = 4 s, where crossing counts from 12.1 mm), 2-7 arrested (2.27 mm past at t = 4
// s, its interface never wet; 62 min), 2-8 crossed (22.7 mm past at t = 3.4 s: the same miss as at
// 3 mm), 2-2 crossed (39 mm past at t = 4 s; 24 min on one thread, 2026-11-25), S-1 crossed (34.8
// mm past the plane at t = 0.9 s, 58.9 mm when the fluid broke through at t = 1.0 s; 19 min to
// there, 2026-11-25), 2-5 dilated (its interface open and wet from t = 1.6 s with the borehole at
// 7.00 MPa, along 46.5 mm at t = 4 s; broken rock 2.0 mm past the plane; 30 min), 2-3 dilated (from
// t = 1.6 s, p = 7.00 MPa; open and wet along 39.3 mm at t = 4 s, broken rock 3.3 mm past; 27 min;
// 2026-11-25): 8 of 9 as the experiment, as at 3 mm. S-2 (no experiment; 2026-11-26) crossed+dilated:
// its interface open and wet from t = 2.2 s (35 mm at t = 3.3 s), and broken rock 12.7 mm past the
// plane at t = 3.3 s, where crossing counts from 12.1 mm (at 3 mm it read dilated, 10.6 mm past at t =
// 4 s under that spacing's 18.1): the one row whose two horizons disagree. With traction faces: 2-1 crossed
// (35 mm past the plane at t = 4 s) and 2-2 crossed (25 mm past at t = 3.4 s); before the fix of
// the junction 2-4 crossed (30.1 mm) and S-1 crossed (25.7 mm at t = 0.6 s).
// Before the guar (the lumped fluid, 2026-11-23 and before): 5 of 9, 2-6 arrested as its free wing
// vented first, 2-8 and 2-3 crossed and 2-5 arrested with the fluid at 5.6-5.9 MPa, below their
// sigma_n (with T = 5 MPa also 5 of 9).
// The outcome is the record of the whole run (geomech/interface_outcome.hpp: an interface once open and
// wet stays dilated, as the cut block shows the faces the fluid wetted), up to the end or to the load
// step in which the fluid breaks through to the block's faces: the laboratory test ended there, its
// pressure lost, and that load step breaks no more bonds after it (pd/dynamic_relaxation.hpp). The case writes zhou_crossing.csv with the columns test,
// approach_angle_deg, sigma_H_MPa, sigma_h_MPa, outcome_experiment, outcome_thesis_pd, outcome_rift
// (and the second horizon's), the damage of each run as zhou_crossing_<test>.csv (x, y, damage) for
// the panel validation/run draws, and each row's scene at each spacing as zhou_<test>_<spacing>mm.toml
// (`rift run` on it gives the history load step by load step). RIFT_ZHOU_ROWS="2-1,S-1" runs those
// rows only and RIFT_ZHOU_ROWS=none writes the scenes alone; either fails, as every row with an
// experiment counts.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "case.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/forces.hpp"
#include "rift/geomech/interface_outcome.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

namespace {

struct ZhouTest {
  const char* test;
  double angle_deg, sigma_H, sigma_h;  // MPa, compression positive
  const char* experiment;              // "" where the row has no experiment
  const char* thesis;
};

// zhou2008_crossing_tests.csv
const std::array<ZhouTest, 10> zhou_tests{{
    {"2-1", 90, 10, 5, "crossed", ""},
    {"2-2", 90, 10, 3, "crossed", ""},
    {"2-4", 60, 10, 3, "crossed", "crossed"},
    {"2-6", 60, 13, 3, "crossed", "crossed"},
    {"S-1", 60, 15, 0, "crossed", "crossed"},
    {"2-8", 60, 8, 5, "dilated", "crossed+dilated"},
    {"S-2", 45, 8, 5, "", "dilated"},
    {"2-3", 30, 10, 5, "dilated", ""},
    {"2-5", 30, 8, 5, "dilated", ""},
    {"2-7", 30, 13, 3, "arrested", "arrested"},
}};

std::string zhou_scene(const ZhouTest& t, double spacing) {
  const double a = t.angle_deg * M_PI / 180.0, distance = 0.075;
  const double half = 0.15 - 3.0 * spacing;  // the interface ends this far inside the block
  auto reach = [&](double along_x) {          // how far along the interface to the block's edge
    const double by_y = std::sin(a) > 1e-9 ? half / std::sin(a) : 1e9;
    const double by_x = std::abs(std::cos(a)) > 1e-9 ? along_x / std::abs(std::cos(a)) : 1e9;
    return std::min(by_y, by_x);
  };
  const double up = reach(half - distance), down = reach(half + distance);
  const double x0 = distance - down * std::cos(a), y0 = -down * std::sin(a);
  const double x1 = distance + up * std::cos(a), y1 = up * std::sin(a);
  char text[2400];
  std::snprintf(text, sizeof text, R"([scene]
name = "zhou_%s"
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "lps"
density = 2300.0
youngs_modulus = 8.402e9
poisson_ratio = 0.23
bond_failure = "normal_stress"
tensile_strength = 3e6
[regions.block]
shape = "box"
min = [-0.15, -0.15]
max = [0.15, 0.15]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.003
[bodies.rock]
material = "rock"
region = "block"
spacing = %.17g
horizon = 3.015
lattice_origin = [%.17g, 0.0]
[[cracks]]
points = [[-0.012, 0.0], [0.012, 0.0]]
[[boreholes]]
region = "hole"
injection_rate = 3e-9
fluid_bulk_modulus = 2.2e9
fluid_viscosity = 0.135
[[interfaces]]
points = [[%.9f, %.9f], [%.9f, %.9f]]
tensile_strength = 1e6
cohesion = 0.0
friction_coefficient = 0.89
[in_situ_stress]
sigma_H = %.17g
sigma_h = %.17g
faces = "platens"
[contact]
distance = 1.0
[solver]
type = "dynamic_relaxation"
end_time = 4.0
load_steps = 40
max_iterations = 6000
tolerance = 1e-5
breaking = "at_equilibrium"
max_breaking_passes = 50
)",
                t.test, spacing, -0.5 * spacing, x0, y0, x1, y1, -t.sigma_H * 1e6, -t.sigma_h * 1e6);
  return text;
}

struct ZhouRun {
  geomech::InterfaceOutcome outcome;
  int unconverged = 0;
};

ZhouRun run_zhou(const ZhouTest& t, double spacing, const std::string& damage_csv) {
  const auto s = scene::parse_string(zhou_scene(t, spacing), "zhou.toml");
  run::Simulation<2> sim(s);
  auto& m = sim.model;
  sim.equilibrate_in_situ(s.in_situ);
  pd::DynamicRelaxation<2> dr(m);
  ZhouRun out;
  std::vector<double> damage;
  const std::size_t source = s.cracks.size();  // the borehole's fluid
  for (long step = 1; step <= sim.steps; ++step) {
    const double time = s.solver.end_time * double(step) / double(sim.steps);
    const auto r = sim.relax(dr, s.solver, time);
    // the test ends when the fracture reaches the block's faces and the fluid escapes, as the
    // laboratory test did (its pressure lost): the load step's bonds stop breaking then
    // (pd/dynamic_relaxation.hpp) and the outcome is the block's at that moment
    const bool broke_through = m.fluid_network.broke_through.at(source) != 0;
    out.unconverged += r.converged || broke_through ? 0 : 1;
    pd::update_damage<2>(m);
    std::vector<geomech::InterfaceOutcome> record{out.outcome};  // what a cut block shows: the fluid's path so far
    geomech::record_outcomes(record, geomech::classify_interfaces<2>(m));
    out.outcome = record.at(0);
    damage = m.damage;
    if (broke_through) break;
  }
  if (!damage_csv.empty()) {
    std::ofstream f(damage_csv);
    f << "x,y,damage\n";
    for (std::size_t i = 0; i < damage.size(); ++i)
      if (damage[i] > 0.05) f << m.reference_position[i][0] << "," << m.reference_position[i][1] << "," << damage[i] << "\n";
  }
  return out;
}

}  // namespace

Result hf_zhou_crossing(const Settings& settings) {
  // two horizons at horizon / spacing = 3.015 (quick: the coarse one and a coarser one)
  const std::array<double, 2> spacings = settings.quick ? std::array<double, 2>{0.003, 0.002} : std::array<double, 2>{0.002, 0.0015};
  std::vector<std::array<std::string, 2>> outcomes;
  // every row with an experiment counts, run or not: a partial run (RIFT_ZHOU_ROWS) does not pass
  int matched = 0, with_experiment = 0, unconverged = 0;
  for (const auto& t : zhou_tests) with_experiment += *t.experiment ? 1 : 0;
  bool both_agree = true;
  // RIFT_ZHOU_ROWS="2-1,S-1" runs those rows only (the rest read "not run"), for runs of a few rows
  const char* rows = std::getenv("RIFT_ZHOU_ROWS");
  auto selected = [&](const std::string& test) {
    if (!rows || !*rows) return true;
    const std::string list = std::string(",") + rows + ",";
    return list.find("," + test + ",") != std::string::npos;
  };
  // each row's scene, for `rift run` (its history and fields load step by load step)
  if (!settings.output_dir.empty())
    for (const auto& t : zhou_tests)
      for (double spacing : spacings) {
        char name[200];
        std::snprintf(name, sizeof name, "%s/zhou_%s_%gmm.toml", settings.output_dir.c_str(), t.test, spacing * 1e3);
        std::ofstream(name) << zhou_scene(t, spacing);
      }
  for (const auto& t : zhou_tests) {
    std::array<std::string, 2> o{"not run", "not run"};
    if (!selected(t.test)) {
      both_agree = false;
      outcomes.push_back(o);
      continue;
    }
    for (std::size_t h = 0; h < 2; ++h) {
      std::string csv;
      if (!settings.output_dir.empty() && h == 0) csv = settings.output_dir + "/zhou_crossing_" + t.test + ".csv";
      const auto r = run_zhou(t, spacings[h], csv);
      o[h] = r.outcome.name();
      unconverged += r.unconverged;
      // a row takes minutes: each is printed as it ends
      std::fprintf(stderr, "hf_zhou_crossing %s at %.3g mm spacing: %s (experiment %s), %d load steps without equilibrium\n", t.test,
                   spacings[h] * 1e3, o[h].c_str(), *t.experiment ? t.experiment : "-", r.unconverged);
    }
    if (*t.experiment && o[0] == t.experiment && o[1] == t.experiment) ++matched;
    both_agree = both_agree && o[0] == o[1];
    outcomes.push_back(o);
  }
  if (!settings.output_dir.empty()) {
    std::ofstream f(settings.output_dir + "/zhou_crossing.csv");
    char header[200];
    std::snprintf(header, sizeof header, "test,approach_angle_deg,sigma_H_MPa,sigma_h_MPa,outcome_experiment,outcome_thesis_pd,outcome_rift,outcome_rift_horizon_%.3gmm\n",
                  3.015 * spacings[1] * 1e3);
    f << header;
    for (std::size_t k = 0; k < zhou_tests.size(); ++k) {
      const auto& t = zhou_tests[k];
      f << t.test << "," << t.angle_deg << "," << t.sigma_H << "," << t.sigma_h << "," << t.experiment << "," << t.thesis << ","
        << outcomes[k][0] << "," << outcomes[k][1] << "\n";
    }
  }
  std::string table;
  for (std::size_t k = 0; k < zhou_tests.size(); ++k) {
    const auto& t = zhou_tests[k];
    table += (k ? "; " : "") + std::string(t.test) + " " + (*t.experiment ? t.experiment : "-") + " -> " + outcomes[k][0] + " / " + outcomes[k][1];
  }
  Result r;
  r.name = "hf_zhou_crossing";
  r.measured = matched;
  r.reference = with_experiment;
  r.tolerance = 0.0;
  r.unit = "tests whose outcome matches the experiment at both horizons";
  char tail[300];
  std::snprintf(tail, sizeof tail, " (experiment -> rift at horizon %.3g / %.3g mm); the two horizons agree on every row: %s; load steps without equilibrium: %d",
                3.015 * spacings[0] * 1e3, 3.015 * spacings[1] * 1e3, both_agree ? "yes" : "NO", unconverged);
  r.details = table + tail;
  r.source = "Zhou et al. (2008) tri-axial hydraulic fracturing tests (thesis Table 4.2)";
  r.decide();
  return r;
}

// The coarse version for CI: test 2-1 (90 degrees, 10 / 5 MPa: crossed) as the table runs it at 3
// mm (4 min on one thread). Measured with the platens: crossed, 36 mm past the interface at t = 4 s
// (30 mm with traction faces; 28.5 mm before the fluid was let through the junction, when a column
// of sites on the interface bridged it). At 4 mm spacing (horizon 12 mm, measured before that) the
// guar's 2-1 stops 1 mm past the plane (2-7 arrests there as at 3 mm) and the two rows take 13 min;
// 2-7 takes 13-20 min at 3 mm.
Result hf_zhou_crossing_coarse(const Settings&) {
  const double spacing = 0.003;
  int matched = 0;
  std::string details;
  for (const char* test : {"2-1"}) {
    const auto& t = *std::find_if(zhou_tests.begin(), zhou_tests.end(), [&](const ZhouTest& z) { return std::string(z.test) == test; });
    const auto r = run_zhou(t, spacing, "");
    const std::string outcome = r.outcome.name();
    matched += outcome == t.experiment ? 1 : 0;
    char line[240];
    std::snprintf(line, sizeof line, "%s%s %s -> %s (%.3g mm past the plane, open and wet along %.3g mm)", details.empty() ? "" : "; ", t.test,
                  t.experiment, outcome.c_str(), 1e3 * r.outcome.crossing_distance, 1e3 * r.outcome.opened_length);
    details += line;
  }
  Result r;
  r.name = "hf_zhou_crossing_coarse";
  r.measured = matched;
  r.reference = 1;
  r.tolerance = 0.0;
  r.unit = "tests whose outcome matches the experiment (2-1 at 3 mm spacing)";
  r.details = details;
  r.source = "Zhou et al. (2008) tri-axial hydraulic fracturing tests (thesis Table 4.2)";
  r.decide();
  return r;
}

}  // namespace rift::validation

"""Cited figures for walk surfaces, steps, stairs, ramps and headroom (metres, radians).

One place for the numbers :mod:`mjwalk.world.surfaces` and :mod:`mjwalk.world.levels` decide with,
and that planners and gait models on several levels can compare a walker with. Each figure names
its source; where a source could not be checked from here the comment says so. ASR A1.8
"Verkehrswege" (2012, amended 2018) refers stair geometry to DIN 18065; the DIN 18065 figures
below were checked against public summaries of the 2015/2020 editions, not the standard itself.
"""

from __future__ import annotations

import math

# --- comparing computed lengths with these limits ---------------------------------------------
#: Slack, metres, on every comparison of a length computed from geoms' corners (a riser, a tread,
#: a surface's depth or width) with a limit of this module: the float rounding of the corners,
#: not a tolerance of the norm. A generated hall's 0.19 m riser, exactly ``MAX_RISER``, came out
#: 0.19000000000000006 m, and its flight and mezzanine were no walk surfaces
#: (``benchmarks/bench_unseen.py``, hall 214). MuJoCo stores mesh vertices in single precision
#: (``mjModel.mesh_vert`` is float32, rounded to 2^-24 of their size, about their mesh's centre):
#: a CAD tread exactly 0.26 m deep (``MIN_TREAD``) measured 0.2599999x m and was no walk surface,
#: and a mesh flight's 0.19 m risers 0.19000006 m (helper spiral47). A vertex up to 8 m from its
#: mesh's centre is off by up to 2^-24 x 8 m = 4.8e-7 m, a length between two such vertices
#: about 1e-6 m: that is the slack. Far below any measurement's precision (a scan's 5 mm noise,
#: DIN 18065's 5 mm build tolerance).
ROUNDING_SLACK = 1e-6

# --- stairs and steps -------------------------------------------------------------------------
#: Smallest and largest riser (Steigung) of a building stair, metres: DIN 18065:2020 Table 1,
#: "Gebäude im Allgemeinen" (workplaces, offices, public buildings), 140-190 mm; ASR A1.8 §4.5
#: takes the same range for workplace stairs (the ASR table itself not verifiable here).
MIN_RISER = 0.14
MAX_RISER = 0.19
#: Smallest and largest tread (Auftritt) of a building stair, metres: DIN 18065:2020 Table 1,
#: buildings in general, 260-370 mm. A horizontal surface no deeper than ``MAX_TREAD`` is a tread.
MIN_TREAD = 0.26
MAX_TREAD = 0.37
#: Step rule (Schrittmaßregel) 2 s + a, metres: 0.59-0.65 m, DIN 18065 (required) and ASR A1.8
#: §4.5 (recommended), the mean step length of a walker; ASR A1.8 names s = 0.17, a = 0.29 as
#: particularly safe (2 s + a = 0.63 m).
STEP_RULE = (0.59, 0.65)
#: Most a riser or tread of one flight may differ from its nominal value and from its neighbour,
#: metres: DIN 18065 tolerance, 5 mm (DIN 18065 §7, figures A.21/A.22, as summarised at
#: https://treppenmeister.com/de/treppenlexikon/toleranzen and
#: https://www.treppenportal-deutschland.de/treppenberater/toleranzen.php: the actual riser and
#: tread of a finished flight within 5 mm of the nominal and of the next step's; 15 mm for the
#: first riser of prefabricated flights in houses of up to two dwellings, not workplaces; the
#: standard itself not verifiable here). It bounds how regular a flight is, never its limits:
#: the tolerances may not, besides, exceed or fall short of the limit dimensions (the largest
#: and least figures the building rules set; treppenmeister.com, above, translated). So a
#: flight with a riser over :data:`MAX_RISER`, a tread outside :data:`MIN_TREAD`-
#: :data:`MAX_TREAD` or a step rule outside :data:`STEP_RULE`, by however little, is no stair
#: (``mjwalk.world.levels``); a scan's measured flight has its own slack for the grid and the
#: noise (``mjwalk.scan.stairfit``), and is written inside the limits.
STAIR_TOLERANCE = 0.005
#: Fewest risers of a flight (Treppenlauf): DIN 18065 defines a flight as at least three risers;
#: one or two are single steps.
MIN_STAIR_RISERS = 3

#: Least depth of a turned (winder or spiral) tread at its narrow end, within the usable width,
#: metres: DIN 18065:2020, "Gebäude im Allgemeinen", 100 mm (50 mm within dwellings and houses
#: of up to two dwellings), as summarised at https://treppen-abc.com/de/treppenlexikon/
#: gewendelte-stufen (the standard itself not verifiable here). Such a tread is measured on the
#: walk line ("Lauflinie"), which for usable widths up to 1 m lies in the middle of the stair
#: (the walk zone is the middle 2/10 of the width; https://treppenakademie.de/wissensdatenbank/
#: lauflinie-bei-treppen/), as the chord between its crossings of the two nosings
#: (https://treppenbau-voss.de/n%C3%BCtzliches/treppen-abc/gewendelt), and must meet
#: :data:`MIN_TREAD`-:data:`MAX_TREAD` and :data:`STEP_RULE` there (:mod:`mjwalk.world.walkline`).
WINDER_MIN_NARROW_TREAD = 0.10
#: Least depth of the part of a turned tread that counts to a stair's usable width, metres: on a
#: spiral stair ("Spindeltreppe", a winder round a central post; DIN 18065) the part of the
#: treads towards the post that is shallower than the 100 mm least tread does not count to the
#: usable width (https://www.baunetzwissen.de/treppen/fachwissen/treppenformen/
#: spindeltreppen-3375193: "Der Teil der Stufen, der zur Spindel hin den Mindestauftritt von
#: 10 cm unterschreitet, zählt nicht zur nutzbaren Treppenlaufbreite"; treppen-abc.com's
#: Spindeltreppen page: the usable width from 100 mm tread, after DIN 18065; the standard itself
#: not verifiable here). So the narrow-end rule holds within the usable width by its definition,
#: and the walk line lies in the middle of that width (:mod:`mjwalk.world.walkline`), as on any
#: turning stair up to 1 m wide (above); the same Baunetz page advises a spiral's walk line
#: "etwa 4/10" of the usable width from the handrail side, the edge of the middle 2/10 walk
#: zone (:data:`WALK_ZONE_SHARE`) the middle lies in, so the feet may move there; a stair
#: no stretch of whose width is this deep on every tread keeps its narrow-end fault. Such stairs
#: are secondary stairs in workplaces: ASR A1.8 (as its predecessor ASR 17/1,2 §3.2, quoted at
#: https://brandschutzfachplaner.de/flarum/d/1267-spindeltreppen_in_arbeitsst%C3%A4tten_unzul%C3%A4ssig)
#: admits spiral stairs only as additional, not necessary, stairs; mjwalk measures them against
#: the limits above all the same (a walk-line tread :data:`MIN_TREAD`-:data:`MAX_TREAD`, risers
#: up to :data:`MAX_RISER`, :data:`STEP_RULE`), stricter than DIN 18065 Table 1's figures for
#: additional stairs as public summaries give them (risers to 0.21 m, treads from 0.21 m;
#: https://www.hausjournal.net/treppenstufen-tiefe; not verified against the standard).
USABLE_TREAD_DEPTH = WINDER_MIN_NARROW_TREAD
#: Width of a turning stair's walk zone ("Gehbereich") as a share of its usable width: the
#: middle 2/10 for usable widths up to 1 m (DIN 18065:2020, as summarised at
#: https://treppenakademie.de/wissensdatenbank/lauflinie-bei-treppen/; the standard itself not
#: verifiable here). People walk a winder within it; a foot that does not fit its tread on the
#: walk line is placed elsewhere in it (:mod:`mjwalk.plan.windercross`).
WALK_ZONE_SHARE = 0.2

#: Room people leave between their body and the side of a stair (a wall or the side of the
#: treads), metres: the boundary layer of Pauls' effective-width model, 0.15 m for "stairways,
#: wall or side of tread" (Pauls 1980; SFPE Handbook of Fire Protection Engineering, "Emergency
#: Movement", table of boundary-layer widths; 0.09 m from a handrail's centreline; NOT verified
#: here). A walker on a stair, ramp or step keeps its swinging arms this far from its sides.
SIDE_CLEARANCE = 0.15
#: Least vertical clearance of the swing foot's sole over a step edge (nosing), metres. Young
#: adults' minimum foot clearance over stair nosings is a few centimetres: Hamel, Okita,
#: Higginson & Cavanagh, "Foot clearance during stair descent: effects of age and
#: illumination", Gait Posture 21:135-140 (2005) count clearances under 5 mm as the risky ones
#: (abstract verified here); Francksen et al., "Negotiating stairs with an inconsistent riser",
#: Applied Ergonomics (2022) report that a 10 mm higher riser cuts ascent clearance by ~9 mm
#: (highlights verified here), a trip risk, so the usual clearance is not much larger; the
#: group means of 3-4 cm usually quoted from these studies are NOT verified here. 3 cm.
STAIR_TOE_CLEARANCE = 0.03
#: Least vertical clearance of the swing foot's sole over a nosing going DOWN a stair, metres:
#: the bound below which stair-descent studies count a clearance as low (a trip risk), not a
#: typical clearance. Hamel, Okita, Higginson & Cavanagh, "Foot clearance during stair descent:
#: effects of age and illumination", Gait Posture 21:135-140 (2005): older adults had
#: significantly more minimum foot clearances under 5 mm than young adults (abstract verified
#: here); Foster, Hotchkiss, Buckley & Elliott, "Safety on stairs: influence of a tread edge
#: highlighter and its position", Exp Gerontol 55:152-158 (2014): in older adults (71 +- 7 y)
#: 2 % of descent clearances were under 5 mm with a highlighter flush with the nosing and 17 %
#: with it set back 30 mm; in young adults with simulated cataract 8 % without a highlighter,
#: 0 % with a flush one (abstract verified here). No published descent clearance mean or range
#: was found in the stored sources (searched: Hamel et al. 2005, Simoneau et al. 1991, Christina
#: & Cavanagh 2002, Zietz, Johannsen & Hollands 2011, Loverro, Mueske & Hamel 2013, Cluff &
#: Robertson, Muhaidat et al. 2011, Foster et al. 2014, Di Giulio et al. 2020: abstracts only),
#: so :data:`STAIR_TOE_CLEARANCE` remains an ascent figure. 5 mm.
DESCENT_LOW_CLEARANCE = 0.005
#: Least share of a foot's length that stands on its tread, on a straight flight and on a
#: winder alike: the part of the sole towards the riser at the tread's back (the toes going
#: up, the heel going down) within the tread, the rest hanging over the tread's own nosing
#: (the heel back over it going up, the toes forward over it going down). Slips, falls and
#: injuries on stairs are more likely where a walker "oversteps, placing only 50-60 % of their
#: foot on the tread", and rare beyond a 300 mm going (able-2.co.uk, "Solutions when the tread
#: of the step is too narrow", occupational-therapy advice quoting stair research without
#: naming it; NOT verified against that research). The studies found measure the same
#: quantity but give no threshold in what could be read here: foot overhang as a percentage
#: of foot length grows as the going shrinks from 325 to 175 mm, up and down (Di Giulio et al.,
#: Front. Sports Act. Living 2:63, 2020), a 3 % shorter foot contact length in descent
#: raises the risk of an overstep (Francksen et al., Appl. Ergon. 87:103131, 2020), overhang
#: counted in percent of foot length (Muhaidat et al., Gait Posture 33:504, 2011), larger
#: goings prevent serious trips (Roys, Appl. Ergon. 32:135, 2001): abstracts only; Templer
#: 1992, Jackson & Cohen 1995 and Wright & Roys not found. The top of that 50-60 % band: 0.6.
#: It agrees with DIN 18065 (going >= 0.26 m, or 0.23 m with >= 30 mm nosing projection
#: (Unterschneidung), as summarised at treppenprofi-hamburg.de/faq-items/untertritt and
#: treppen-abc.com/de/treppenlexikon/treppenauftritt): 0.26 m of tread is shorter than a
#: tall adult's shoe, so the standard accepts some overhang on every conforming flight, and
#: at 0.6 every walker up to 2.2 m (mjwalk.gait.walker.STATURE_RANGE) keeps a conforming
#: straight flight (``mjwalk.plan.treadshare``: 0.26 m less 35 mm of gaps is 0.67 of a
#: 2.2 m walker's 0.334 m foot).
MIN_TREAD_SHARE = 0.6

# --- level and touching surfaces --------------------------------------------------------------
#: Largest height difference between two touching surfaces that still counts as one level,
#: metres: ASR A1.5/1,2 "Fußböden" §3.4, height differences over 4 mm are already trip points.
LEVEL_TOLERANCE = 0.004
#: Widest gap between two surfaces' edges that still joins them, metres: ASR A1.5/1,2, gaps in a
#: floor wider than 20 mm are trip points (so narrower gaps are walked over).
CONTACT_GAP = 0.02
#: Largest slope of a surface that counts as horizontal (rise over run): DIN 18065 tolerates
#: treads deviating at most 1 % from the horizontal.
HORIZONTAL_SLOPE = 0.01

# --- ramps ------------------------------------------------------------------------------------
#: Steepest walk surface that is a ramp, radians: 10 deg. ISO 14122-1/-2 (permanent means of
#: access to machinery) choose a ramp for 0-20 deg and prefer at most 10 deg (steeper ramps need
#: cleats). ASR A1.8's own ramp limit could not be verified here.
MAX_RAMP_SLOPE = math.radians(10.0)
#: Slack, radians, on comparing a slope computed from a face's corners with a slope limit: the
#: corners' :data:`ROUNDING_SLACK` over the shallowest walk surface's depth (:data:`MIN_TREAD`),
#: 3.8e-6 rad (0.0002 deg). A box turned by exactly 10 deg (``euler="0 -10 0"``) measured
#: 0.17453292519943317 rad, 2e-16 over ``MAX_RAMP_SLOPE``, and was no walk surface.
SLOPE_ROUNDING_SLACK = ROUNDING_SLACK / MIN_TREAD
#: Steepest barrier-free ramp, radians: DIN 18040-1:2010 §4.3.8, at most 6 % (atan 0.06,
#: 3.43 deg), for walkers with rollators or wheelchairs; a stricter limit a planner may apply.
BARRIER_FREE_RAMP_SLOPE = math.atan(0.06)

# --- standing room and headroom ---------------------------------------------------------------
#: Narrowest surface a person stands on across the shoulders, metres: the shoulder breadth of a
#: 95th-percentile man, about 0.52 m (DIN 33402-2), rounded up to 0.6 m, as the scan's
#: ``mjwalk.scan.level.STAND_AREA`` (0.6 m square) is.
STAND_WIDTH = 0.60
#: Smallest floor, square metres: room for one person to stand and turn (0.8 m x 1.25 m
#: turning space of ISO 21542 rounded down); a scan's floor (``mjwalk.scan.level``) and a slab
#: floor (``mjwalk.world.slabfloor``) are at least this large.
MIN_FLOOR_AREA = 1.0
#: The floor is the *large* walkable region at the lowest level (seed paper §3): a walk surface
#: smaller than this share of the largest is no floor (a scan's surfaces below the floor are
#: ignored, a slab top is no candidate).
FLOOR_SHARE = 0.25
#: Clear headroom over a walk surface, metres: DIN 18065 lichte Treppendurchgangshöhe, at least
#: 2.00 m; ASR A1.8 asks the same clear height over walkways (not verified here).
CLEAR_HEADROOM = 2.00
#: What a walker's head needs above the stature, metres: shoes add up to 45 mm (women's; 25 mm
#: for men) and a protective helmet 35 mm (Pheasant & Haslegrave, "Bodyspace", corrections to
#: standing dimensions), 0.045 + 0.035 = 0.08 m.
HEAD_MARGIN = 0.08
#: Free heights below this are obstacles for every walker, not ceilings some walk under, metres:
#: the shortest stature mjwalk draws (``mjwalk.gait.walker.STATURE_RANGE``, 1.2 m).
OVERHEAD_MIN = 1.20
#: How far above a surface geoms are looked for, metres: the tallest stature mjwalk draws (2.2 m)
#: plus :data:`HEAD_MARGIN`, rounded up; nothing within it means an open ceiling (inf).
HEADROOM_SCAN = 2.5
#: The foot of the obstacle band (``mjwalk.world.floor.OBSTACLE_Z_RANGE``): a surface beyond an
#: edge counts as one to step onto only where more than this is free above it, metres.
EXPOSED_MIN = 0.05

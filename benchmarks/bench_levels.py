"""Stair and ramp gait per walker profile beside the cited norms (issue 47, deliverable 3).

Run: python3 benchmarks/bench_levels.py [--draws 400] [--seed 47]

For every walker preset (mjwalk.gait.walker.PRESETS), ``--draws`` operators drawn as the cycle
draws them (mjwalk.cycle.population), on the issue's stair (0.17 m risers, 0.28 m treads, six
risers to the 1.02 m mezzanine) and ramp (5.5 deg to the 0.34 m platform): the group mean (and
5th-95th percentiles) of the time per step, the cadence and the speeds, and the time for the
flight and the ramp, printed beside the cited norms (Fruin 1971 stair speeds along the slope;
Oh-Park et al. 2011 per-step stair times of adults of 70 and over).

Then the planning cost of walks over levels (``--walks`` seeds per pair, after one warm-up plan
each): the wall-clock time of ``plan_walk`` between sites on different levels of
scenes/multilevel_station.xml (level route, hybrid A* per level, crossings) against a flat walk
of the same walked length planned along scenes/open_floor.xml's diagonal, median over the
seeds, and their ratio (target: at most 1.5, issue 47).

Measured (400 walkers per group, seed 47, 2 s): group-mean speed along the slope up / down,
m/s: adult 0.575 / 0.725, older_adult 0.518 / 0.653, fatigued 0.517 / 0.652 (all inside
Fruin's 0.485-0.67 / 0.595-1.01), brisk 0.686 / 0.864 (up above Fruin's fastest group mean,
as hurrying walkers should be); elderly time per step 0.866 s up / 0.686 s down (inside
Oh-Park's 0.70-1.07 / 0.66-1.23 s). The six-riser flight: adult 3.5 s up, 2.8 s down; elderly
5.2 s / 4.1 s. The 5.5 deg ramp: adult 1.00 m/s up (0.71 of level), 1.40 m/s down.

Legs on the stair (``--draws 50 --walks 0``, branch i47-swing4): up, knee peak 101.6-103.5 deg
(cited 83-105), hip 56.0-57.5 (55-75), least toe clearance over the nosings 3.0 cm (cited 3 cm);
down, knee 98.6-99.4 (80-100), hip 40.5-41.4 (20-45), clearance 0.3-0.5 cm (the descent foot,
pitched further toes down after its swing is planned, is only kept off the treads). The
synthetic stair walk has 0 contacts up and down in MuJoCo.

Branch hip47 (``--draws 50 --walks 0``): the legs table adds the swing hip as its foot lands
(``hip IC``) and where in the swing the peak lies (``at``), from analysis.swing_hip_peaks;
knee, hip and clearance unchanged (up: hip 55.0-56.4 deg, statures 1.67-1.73 m). Up, the hip
peaks at 0.58-0.59 of the swing (the foot at its highest over the lower nosing) and extends
to 44.8-45.9 deg by foot contact; published ascent hip flexion peaks in late swing and is
held into contact. The "hip" here is the thigh from the vertical (the humanoid's pelvis never
tilts); the cited 55-75 deg are the thigh to the pelvis, which tilts forward 2.6-9.7 deg in
step ascent (Bohannon & Smutnick 2010, abstract): not comparable one to one.

Branch hip47b (``--draws 50 --walks 0``, base 571cdb1 run right before with this script): up
a stair the pelvis tilts forward 2.6 deg (Bohannon & Smutnick's least mean step-ascent tilt,
mjwalk.body.legs.pelvistilt; eased in over the first step, out over the step off the flight)
and the hips are solved in the tilted pelvis, so ``hip`` is now the thigh to the pelvis as
published: up, hip 55.0-56.4 -> 57.6-59.0 deg, hip IC 44.8-45.9 -> 47.4-48.5 (cited 55-75);
knee (100.3-103.7), clearance, ``at`` and every descent and gait figure unchanged.

Branch hip47c (``--draws 50 --walks 0``, base beb62ed run right before with this script): the
tilt is backward (posterior), as the pelvifemoral rhythm Bohannon & Smutnick measured is
defined by its authors (Bohannon & Bass 2017: thigh flexion with posterior pelvic tilt), and the
lumbar joint takes it back in the timeline (the trunk keeps its pose): up, hip 57.6-59.0 ->
52.4-53.8 deg, hip IC 47.4-48.5 -> 42.2-43.3 (cited 55-75: now under it); knee, clearance, ``at``
and every descent and gait figure unchanged.

Branch trunk47 (``--draws 50 --walks 0``, base 2a82a27 run right before with this script): up
a stair the trunk leans forward 12.4 deg in the spine (controls' mean anterior trunk tilt 13.7
deg ascending a 17 cm stair against 1.3 deg walking level, Int J Phys Med Rehabil 2:231 (2014),
Table 3: mjwalk.body.legs.trunklean); the new ``trunk`` column (trunk flexion, hip joint centre
to C7 from the vertical, as the ergonomic methods read it) goes up -0.4 -> 7.9 deg in every
group (the thorax itself leans 12.4 deg; the hip-to-C7 line also runs through the pelvis,
tilted 2.6 deg backward, and the lumbar segment, flexed by 57 % of the lean), down 0.0 -> 0.0;
knee, hip, hip IC, at and clearance unchanged (the lean is the spine's, not the pelvis's).

Branch hip47d (``--draws 50 --walks 0``, base eea2d7c run right before with this script): up
a stair the synthetic walk's pelvis stands at each foot contact midway between the feet (the
points under the ankles), as the level planner's walks put it (plan.footfallwalk), not midway
between the treads' centres, the setback (6.65 cm at 1.75 m) further on: up, hip 52.4-53.8 ->
55.1-56.3 deg (cited 55-75), hip IC 42.2-43.3 -> 43.8-45.0, at 0.58-0.59 -> 0.56-0.58, knee
100.3-103.7 -> 99.7-101.8; clearance, trunk and every descent, ramp and timing figure
unchanged (down keeps the treads' centres: midway between the feet its first step off the
top landing peaks at 100.2 deg knee at 1.75 m, over the cited 100).

Branch descent47 (``--draws 50 --walks 0``, base bebb988's synthetic walk run right before with
this script): down a stair too the synthetic walk's pelvis stands at each foot contact midway
between the feet, as the planner's walk down the station's stair puts it: down, knee 96.8-97.8
-> 100.6-101.7 deg (cited 80-100; the group means' walkers are 1.67-1.73 m, their footprints
placed for 1.75 m), hip 36.7-37.8 -> 43.1-43.9 (20-45), hip IC 21.8-22.0 -> 23.4-23.5,
clearance 0.6-1.2 -> 0.6-0.9 cm; up, trunk, ramp and timing unchanged. The knee peak is the
first step off the top landing from standing (the pelvis still accelerating from rest); on
the flight's steps from tread to tread 99.6 / 100.2 / 100.5 (adult / older adult / elderly
mean walker, 1.728 / 1.698 / 1.668 m). The planner's own walk down the station's stair
(plan_walk mezzanine rack -> rack 1, arriving walking) peaks at 99.2 deg knee, 42.1 hip at
1.75 m (102.8 / 43.6 at 1.55, 95.8 / 40.0 at 1.85, 92.8 / 38.0 at 2.02 m).

Planning cost measured (``--draws 10 --walks 10``, 2-core machine at load average 1.3, three
runs, branch i47-levelcost): median ms level walk / open-floor walk of the same length / the
route's level legs planned alone as flat walks: step 1.6-1.8 / 2.6-2.7 / 2.4-2.6 (ratio to flat
0.62-0.67), ramp 1.6-1.8 / 3.1-4.0 / 2.6-3.1 (0.46-0.52), stair 2.2-2.4 / 2.9-3.1 / 3.6-3.9
(0.73-0.77): within the 1.5x target. stand_rack1 -> stand_mezz_rack 5.7-5.8 / 3.3-3.4 / 6.7-7.4
(1.69-1.73) and stand_platform1 -> stand_car1 11.1-12.8 / 3.1-3.3 / 12.4-12.6 (3.55-3.91) are
NOT: their floor legs (round the stair into its foot; round the platform to the car's side)
cost as much planned alone as flat walks of the station's floor (ratio to the legs alone
0.78-1.02), several times the obstacle-free diagonal: the gap is the hybrid A* on that floor,
not the levels. Before (main 77212f4, same command, loaded machine): 17.9-30.6 ms against
9.6-13.6 ms flat (1.66-2.62), platform1 -> car1 155 ms (12.9).

Since branch plan-cost the times are CPU seconds (``time.process_time``) and the expansions of
all of a walk's searches are printed (``meta["expansions_all"]``). ``--draws 10 --walks 10``:
level/flat 0.61, 0.64, 0.74, 1.88 (rack1 -> mezzanine: 86 expansions against 22 flat) and 3.41
(platform1 -> car1: 615 against 20). Where the latter go, measured: the floor leg from the
step's foot to car1 is routed by the distance field through the 0.58 m gap between the trolley
and the car's rear bumper (walk clearance 0.288 m at its narrowest against the 0.26 m the
pelvis samples must keep); sampled steps rarely thread it, the search floods the open floor
behind it (84 % of the first search's nodes west of x = -3 m, seed 1), and the walks it finds
round the trolley, longer than 1.5x the field's distance, are searched again as loops (2-4
searches a walk). The rack1 leg's arrival heading at the stair's foot is a hairpin round the
stair's side wall: its aimed search spends 21-400 expansions.

Branch i47-lvlcost (a level leg to a stair or step ends a step length before its stance on the
axis, and a stair's walk goes on a step length past its far stance: levelcross.approach_point,
departure), ``--draws 2 --walks 10``, CPU time, machine at load 6-8: level/flat 0.55, 0.48,
0.63, rack1 -> mezzanine 1.01 (43 expansions against 23; 2.69 and 276 on main ae71305, same
command), mezzanine -> rack1 (a new row) 1.09 (20 / 25; its legs alone from the stair's
stance, as main walks them, 47.7 ms: 2540 expansions median at ae71305, loops re-searched up to
11.7 m), platform1 -> car1 1.85 (194 / 18, unchanged: its floor leg threads the 0.58 m
trolley-bumper gap; a flat walk on the same floor, stand_step -> stand_car1, 4.5 m, costs 733
expansions and 16.7 ms median over seeds 1-10, more than this 6.4 m walk over levels).

Branch levels47 (``--draws 2 --walks 10``, CPU ms, load 8-14): each side now timed cold (a
seed's first plan) and warm (the same again), the same way. Level / flat, cold: 1.8/7.2,
1.9/8.5, 2.3/8.3, 4.5/9.3, 4.0/9.5, 11.7/8.9 (ratios 0.22-0.48, platform1 -> car1 1.33): the
flat walk's goal moves with each seed's length, so its cold plan builds its goal's distance
field, while the level legs' goals (crossing stances, sites) were built by the warm-up. Warm
(every field kept on both sides): 1.9/0.9, 1.9/1.4, 2.4/1.3, 4.3/1.7, 3.7/2.0, 12.1/1.8 (ratios
2.12, 1.32, 1.87, 2.56, 1.90, 6.86): the searches and the level machinery (two level searches,
the crossing's walk, stitching) against one flat search; the 1.5x target is met cold, not warm.

Branch stairentry47 (``--draws 2 --walks 10``, CPU ms, load 5-9, base a196e73 run right after
with this script): the new ``entry`` column (the sharpest one-step turn onto the first riser or
ramp, max over seeds 1-10): rack1 -> mezzanine 147 -> 60 deg (per seed 106-147 -> 42-60: its
floor leg, a hairpin out of the gap between the stair's east wall and the trolley, ends standing
at the approach point facing away and turns there on the spot, levelcross.spot_turn); the other
rows unchanged (12-22 deg). Expansions unchanged (planning untouched); cold ratios 0.23-1.28
(base 0.24-1.42), warm 0.96-6.01 (base 1.15-7.48): load noise.

Branch stairturn47 (``--draws 2 --walks 10``, CPU ms, base e749e69 run right after with this
script, 2 other jobs on the machine): rack1 -> mezzanine no longer stops and turns on the spot
at the stair's foot: its floor leg turns into the stair while walking (plan.turnin: cut after
one of its last walking steps, Dubins path at 60 deg a step), 10 of 10 seeds (0-9, the walk
7.75 -> 8.61 m; the entry column stays at 60: the turning steps' largest). Cold 5.7 -> 6.1
(ratio 0.58 -> 0.60), warm 5.3 -> 6.1 (2.40 -> 2.87); expansions 46 unchanged (the turn is
placed, not searched: turnin.turn_into 0.8-2.0 ms); the other rows unchanged within noise.
The searches that did not do it, measured (rack1's floor leg to the approach point, seeds
0-9): required heading (goal_yaw) 0/10 in 400 expansions, 3/10 in 1000, 10/10 in 4000 (13,
28, 63 ms); with a Dubins bound added to the heuristic and a guide routed round the wall and
looping into the flight, 1-9/10 in 1000 at 22-42 ms; a heading-conditioned search from 1-2 m
before the leg's end 0-4/10 in 1000. The walks it did find turn on the spot-like short
steps (0.07-0.28 m) next to the approach point: the search's cost of such steps is far above
any metric heuristic, so it floods the floor about the goal.

Branch levelcost47 (``--draws 2 --walks 10``, CPU ms, base 879469c run right before with this
script, load 21-25): the level walk's own costs cut, walks bit-identical (plan.levelmemo keeps a
crossing's footfalls, first footfall and departure, clear lines and option variants;
plan.footfallwalk lays a crossing's steps out at once; turnin traces its Dubins words in order
of fewest steps). rack1 -> mezzanine cold 6.8 -> 5.0 (0.77 -> 0.56), warm 8.2 -> 5.0 (4.50 ->
2.75); the others within noise (warm ratios 1.4-2.4, platform1 -> car1 5.5-5.7: 321 expansions
against 24). Least of 5 repeats per seed, median over seeds 1-10 (two rounds each): step
2.55/2.25 -> 2.30/1.94, rack1 6.13/5.72 -> 4.66/4.66, mezzanine -> rack1 3.93 -> 3.46. What is
left of a warm level walk is mostly its searches (two or three HybridPlanner.plan calls, each
with its guide and assembly, against the flat walk's one): warm 1.5x is not met.

Branch levelwarm47 (b3507ca, ``--draws 2 --walks 10``, CPU ms, load 2-16): cold ratios
0.27-0.96, warm 1.38-6.77 (platform1 -> car1 8.9/1.3 ms, 321 / 24 expansions). Where a warm
level walk's time goes (warm plans of seeds 1-10, three rounds, CPU ms, load 16): step
3.6 = searches 0.7 + guides 0.5 + assembly 0.4 + the rest of two plan calls 0.7 + the
crossing's walk 0.5 + level meta 0.2; the open floor's 2.3 m walk 1.0 (guide 0.04: no
obstacles). platform1 -> car1 13.2, of it searches 8.7. Its expansions are the floor leg's
from the step's foot (-2.83, 3.2) to car1 and do not come from the hand-over: the same leg
planned alone (seeds 1-20, median / mean expansions) from that stance facing west 205 / 376,
facing south 222 / 353, walking south 114 / 470, from stand_step (a flat walk on the same
floor) 429 / 700, from (-2.7, 2.0) facing south already in the passage 256 / 411, from
(-4.0, 1.5) 817 / 1236, and from (-2.3, -0.5) past the trolley 6 / 7. The distance field
routes it through the diagonal passage between the trolley and the car's rear bumper (1-2
pelvis cells of 0.1 m wide, clearance 0.288 m against the 0.25 m radius); sampled steps seldom
thread it, so the search floods the floor north of it or goes round the trolley's west side
(a passage as tight, between it and the stair's east wall) and back, 7-11 m against the
field's 4.24 m, and that walk is searched again as a loop (2-4 searches in 5 of 10 seeds). The
cost is the floor's, the same for a flat walk there; the hybrid search's, not the levels'.

Branch levelcost47h (a88f200, ``--twin-only --walks 20``, CPU ms, load 13-26): each walk
against its flat twin (:func:`flat_twin`: the station with the platform, step, ramp, stair and
mezzanine removed and what stood on them lowered to the floor; the same sites, the same floor
obstacles), median of 20 seeds, level / twin. Warm: step 2.5/1.4 (1.75-1.82), ramp 2.5/1.8
(1.35-1.37), stair 2.8/2.2 (1.24), rack1 -> mezzanine 6.0/2.5 (2.37; the twin walks 3.0 m
straight onto where the mezzanine stood, the level walk 8.5 m round to the stair's foot: per
metre 0.84), mezzanine -> rack1 3.8/2.4 (1.58; per metre 0.59), platform1 -> car1 13.6/42.4
(0.32: 570 / 2560 expansions; the twin, with no platform to walk along, meets the car's rear
and the trolley from the north-east and floods the floor about them). Cold (each side's first
plan in a freshly loaded scene): 690-800 ms against 22-63 ms (ratios 12-33): a flat scene
never builds its levels (~130 ms), its level views (the obstacles clipped to each level's
head band, world.footprint._clip_hull_to_slab, ~35 ms a geom set per view, 3-4 views) nor
the crossings' head checks (~100 ms per stature). The same views and checks are built again
for each new stature (two routes of a new walker in a warm scene: 514 ms old, 523 ms new).
The narrow-gap floor leg (platform1 -> car1) does no work a flat walk does not: planned alone
on the floor's view to car1, seeds 1-40, median / mean / p90 expansions, from the step's foot
standing facing west as the level walk starts it 429 / 595 / 1679; standing facing south 460 /
703 / 1410; from stand_step, the flat walk through the same gap, 330 / 622 / 1373 (the note's
817 was a start at (-4.0, 1.5), not the crossing's foot). Cut here: the route's Dijkstra makes
a node's edges when it pops it (plan.levelsearch), so levels the route never reaches build no
view, field or line-up check; routes and walks bit-identical (1002 comparisons); fresh-scene
first plan, old / new interleaved, 6 seeds: mezzanine -> rack1 742 -> 374 ms, the others
within noise (691-770 -> 670-761): each reaches the floor, the platform and the stair's foot.
Reading of the target: "a flat walk of the same length" is met by both comparators; the twin
is the one that holds what the target measures (the levels' cost) fixed, where its length is
the walk's; warm against it the step (1.75) and rack1 -> mezzanine (per metre 0.84 but 2.37
per walk) rows are over 1.5: the two or three searches, guides and assemblies a level walk
makes against the twin's one (hybrid.py), and cold every row is far over (the levels' set-up).

Branch levelplan47i (13e4664, ``--twin-only --walks 10``, CPU ms, base and branch alternating,
two rounds each, load 9-17; the branch's cold plans start with no footprint kept,
world.footprint.clear_memos): cold, level walk old -> new (twin unchanged, 21-30 ms): step
592/702 -> 495/464, ramp 626/715 -> 471/478, stair 663/715 -> 489/510, rack1 -> mezzanine
729/768 -> 502/578, mezzanine -> rack1 398/374 -> 326/363, platform1 -> car1 776/754 ->
466/470 (ratios 14-32 -> 9-22). Warm unchanged within noise (1.28-2.37). Cuts, walks
bit-identical (108 level walks, 6 pairs x seeds 1-6 x statures 1.55/1.75/1.95, one scene:
same digests): a clipped hull's edges in one NumPy pass (was a Python loop over ~10^4
simplices of a tessellated capsule); hull edges and geom footprints kept per exact key (the
world points' digest and the slab faces that cut them), so a view of another level or head
band clips a geom again without qhull; a crossing's least free height measured once and
compared with every stature. Left: the first 3-D hull of each tessellated geom (the station's
sloped capsule and ellipsoid: ~30-75 ms each), the level graph (world.surfaces, contacts,
walksurface headroom: ~130 ms, modules outside this branch), the views' clearance fields.

Branch levelwarm47j (fc03651, ``--split --walks 10`` at 0bc5342, CPU ms a warm walk, load 3-8):
where a warm walk's time goes. Step walk 2.03 = hybrid plans 1.27 (2 calls: a 0.31 m leg of one
step and a 0.67 m leg of two) + crossing walk 0.27 + record (stitch, level meta) 0.21 + rest
0.28 (route, level legs' set-up, plan_walk); its twin 0.92, of it its one plan 0.69. Ramp 2.00 =
1.23 + 0.29 + 0.22 + 0.26 (twin 1.35); stair 2.27 = 1.44 + 0.31 + 0.24 + 0.28 (twin 1.72);
rack1 -> mezzanine 5.77 = 4.12 (2.1 calls) + 0.34 + 0.29 + turn into the stair 0.68 + 0.33
(twin 2.58). A level leg's plan costs about what the twin's whole plan does (0.6 ms for a
one-step leg: guide, search call, assembly, set-up), so the step row's two plans alone are 1.4x
its twin's walk: no cut of the crossing, record or set-up reaches 1.5x there; one search per
crossing less (the structural change) would leave about 2.03 - 0.6 = 1.4 ms (~1.5x). Cut here,
walks bit-identical (216 digests: 6 pairs x seeds 1-6 x statures 1.55/1.75/1.95, twice each):
a site's endpoint kept (44 -> 0.6 us for a floor site), a crossing's tread setbacks and riser
lines kept (26 -> 1 and 12-33 -> 2-3 us; lines copied per walk), level_meta's crossing length
from the distances it sums anyway (125 -> 89 us): about 0.15 ms a walk. Interleaved, medians of
30 warm plans, base -> branch, two rounds (load 3): step 2.07/2.05 -> 1.79/1.91 ms (ratio
2.39/2.29 -> 2.10/2.20), rack1 -> mezzanine 5.10/4.64 -> 4.10/3.99, mezzanine -> rack1
3.41/3.19 -> 3.02/3.03; at load 11 within noise.

Branch levelcost47k (``--twin-only --walks 10`` and ``--split --walks 10``, CPU ms, base
eea2d7c and branch interleaved, two rounds each, load 4-6): a level leg of at most two step
lengths along a line the body clears, turning within a step at either end, is walked as
footfalls along that line (plan.shortleg, levelcross.line_clear, footfallwalk.footfall_walk;
the last footfall at the leg's goal, the pelvis half a step short, in the goal area), not
searched. Warm level / twin, base -> branch: step 2.2/1.1, 1.7/0.9 -> 1.2/1.2, 0.8/0.9 (ratio
2.02, 1.74 -> 1.01, 0.91; expansions 6 -> 0), ramp 1.47, 1.32 -> 0.79, 0.77 (6 -> 0), stair
1.19, 1.16 -> 0.77, 0.57 (8 -> 0), rack1 -> mezzanine 2.16, 1.95 -> 1.66, 1.63 (46 -> 27: its
mezzanine leg unsearched, its floor leg searched; per metre 0.77, 0.70 -> 0.60, 0.59),
mezzanine -> rack1 1.55, 1.52 -> 1.34, 1.29 (22 -> 13), platform1 -> car1 0.34, 0.30 -> 0.32,
0.29. Split, base -> branch: step 1.48 ms (hybrid plans 0.88, 2 calls) -> 0.76 (0 calls; the
short legs in "rest", 0.26 -> 0.46), twin 0.65; rack1 -> mezzanine 4.42 (2.1 calls) -> 3.65
(1.1). Only rack1 -> mezzanine stays over 1.5 warm (its twin walks 3.0 m, it 8.5 m round to
the stair's foot). Cold unchanged (4.2-5.4, the levels' set-up). Walks change where a leg is
short (no sway or drawn pace on it: even footfalls at the walker's step length and time).

Branch stair47 (``--draws 50 --walks 0``, ba1cbe5's product): the legs table adds ``riser/leg``,
the riser over the group's mean walker's leg (thigh + shank): 0.200 / 0.204 / 0.208 / 0.200 /
0.200 (adult, older adult, elderly, fatigued, brisk; 0.198 at 1.75 m). The norms stay the
fixed adult ranges: the stature / step-height ratio sets the stair range (J Hum Kinet 26:45,
abstract only, no figures), no cited range for another ratio was found (docs/decisions/115).
Every figure unchanged: down, knee 100.6-101.7 deg (over the cited 100: the first step off the
top landing from standing), hip 43.1-43.9; up, knee 99.7-101.8, hip 55.1-56.3.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import tempfile
import time
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path

import mujoco
import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.humanoid import attach_humanoid
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.analysis import swing_hip_peaks
from mjwalk.body.legs.edgeswing import STAIR_TOE_CLEARANCE
from mjwalk.body.legs.legheights import HIP_PEAK_DOWN, HIP_PEAK_UP, KNEE_PEAK_DOWN, KNEE_PEAK_UP
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.cycle.population import Population, preset_group
from mjwalk.ergonomics.angles import angles_from_qpos
from mjwalk.errors import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.gait.slope import slope_gait
from mjwalk.gait.stairs import (
    FRUIN_DOWN_SPEED,
    FRUIN_UP_SPEED,
    OH_PARK_DOWN_STEP_TIME,
    OH_PARK_UP_STEP_TIME,
    StairGeometry,
    stair_gait,
)
from mjwalk.gait.walker import PRESETS, Walker
from mjwalk.plan import levelplan
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.levelplan import STANCE_TOLERANCE, endpoint, level_route, place_crossings
from mjwalk.plan.levelroute import step_up_limit
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.request import WalkRequest
from mjwalk.plan.synthetic import synthetic_stair_walk
from mjwalk.plan.walks import plan_walk
from mjwalk.timeline.frames import frames_from_legs
from mjwalk.world import load_workplace
from mjwalk.world.footprint import clear_memos
from mjwalk.world.levelview import level_view
from mjwalk.world.norms import DESCENT_LOW_CLEARANCE, HEAD_MARGIN

STAIR = StairGeometry(0.17, 0.28)
RISERS = 6
RAMP_DEG = 5.5
RAMP_RISE = 0.34
#: The steepest ramps of the generated halls (mjwalk.world.levelgen: 8.5-9.9 deg), where a long
#: step down is bound by the legs' reach (mjwalk.gait.slope.downhill_step_max).
STEEP_RAMP_DEG = 9.5


def _walkers(group: str, draws: int, seed: int) -> list[Walker]:
    """``draws`` walkers of one preset operator group, drawn as a cycle draws them (seeded)."""
    pop = Population((preset_group(group),))
    rng = np.random.default_rng(seed)
    return [pop.draw(rng) for _ in range(draws)]


def _stats(values: list[float]) -> str:
    a = np.asarray(values)
    lo, hi = np.percentile(a, [5, 95])
    return f"{a.mean():.3f} ({lo:.3f}-{hi:.3f})".ljust(22)


def _norm(group: str, direction: str) -> str:
    if group == "elderly":
        lo, hi = OH_PARK_UP_STEP_TIME if direction == "up" else OH_PARK_DOWN_STEP_TIME
        return f"step {lo:.2f}-{hi:.2f} s (Oh-Park 2011, 70+)"
    lo, hi = FRUIN_UP_SPEED if direction == "up" else FRUIN_DOWN_SPEED
    return f"slope speed {lo:.3f}-{hi:.3f} m/s (Fruin 1971)"


def stair_table(draws: int, seed: int) -> None:
    """Print the stair figures per preset and direction.

    Args:
        draws: walkers per preset.
        seed: the draws' seed.
    """
    print(
        f"\nStair {STAIR.riser} m / {STAIR.tread} m ({math.degrees(STAIR.pitch):.1f} deg), "
        f"{RISERS} risers; mean (5th-95th percentile) over {draws} walkers per group"
    )
    head = (
        f"{'group':12} {'dir':4} {'step time s':22} {'cadence /min':22} "
        f"{'slope speed m/s':22} {'horiz m/s':22} {'flight s':22} norm"
    )
    print(head)
    print("-" * len(head))
    for group in PRESETS:
        walkers = _walkers(group, draws, seed)
        for d in ("up", "down"):
            gaits = [stair_gait(w, STAIR, d) for w in walkers]
            print(
                f"{group:12} {d:4} {_stats([g.step_time for g in gaits])} "
                f"{_stats([g.cadence * 60 for g in gaits])} "
                f"{_stats([g.slope_speed for g in gaits])} "
                f"{_stats([g.horizontal_speed for g in gaits])} "
                f"{_stats([g.flight(RISERS).duration for g in gaits])} {_norm(group, d)}"
            )


_PLANE = '<mujoco><worldbody><geom name="floor" type="plane" size="50 50 .1"/></worldbody></mujoco>'


def trunk_flexion(motion, stature: float, a: int, b: int) -> float:
    """Mean trunk flexion, degrees (the ergonomic methods' hip-to-C7 axis from the vertical in
    the pelvis's sagittal plane, forward +: mjwalk.ergonomics.angles), over every 4th sample
    of ``a:b`` of ``motion`` played by the timeline with swinging arms (frames_from_legs)."""
    model, jm = attach_humanoid(mujoco.MjSpec.from_string(_PLANE), stature)
    t = motion.t[a:b:4]
    q = frames_from_legs(model, jm, motion, t, stature, "swing", None)
    return float(angles_from_qpos(model, jm, q).trunk_flexion.mean())


def _leg(stature: float) -> float:
    """The humanoid's leg length (thigh + shank, m) at ``stature`` metres."""
    g = leg_geometry(stature)
    return g.thigh + g.shank


def body_table(draws: int, seed: int) -> None:
    """Print the legs on the stair per preset: the group's mean walker (mean stature, mean
    step time) played up and down the stair (synthetic_stair_walk, legs_from_walk); knee and
    hip flexion peaks over the flight's inner steps and the least toe clearance over a nosing,
    beside the cited ranges (mjwalk.body.legs.legheights, edgeswing).

    Args:
        draws: walkers per preset.
        seed: the draws' seed.
    """
    print(f"\nLegs on the stair, each group's mean walker ({draws} draws per group)")
    print(
        "hip: the thigh relative to the pelvis, as published hip flexion (the pelvis tilted "
        "backward 2.6 deg up a stair, Bohannon & Smutnick 2010: mjwalk.body.legs.pelvistilt; "
        "upright down it); hip IC: the swing hip as its foot lands; at: the peak's share of "
        "the swing (inner steps, mean); trunk: trunk flexion (hip to C7 from the vertical), "
        "inner steps' mean, the timeline's pose (up a stair leaned 12.4 deg in the spine: "
        "mjwalk.body.legs.trunklean); riser/leg: the riser over the walker's leg (thigh + "
        f"shank; {STAIR.riser / _leg(DEFAULT_STATURE):.3f} at {DEFAULT_STATURE} m). The norms "
        "are adults' of ordinary stature on 17-18 cm risers, not moved with riser/leg: the "
        "stature / step-height ratio sets the stair range (J Hum Kinet 26:45, abstract only) "
        "but no cited range for another ratio was found (docs/decisions/115)"
    )
    head = (
        f"{'group':12} {'dir':4} {'stature m':10} {'riser/leg':10} {'knee deg':9} {'hip deg':8} "
        f"{'hip IC':7} {'at':5} {'clear cm':9} {'trunk':6} norm"
    )
    print(head)
    print("-" * len(head))
    for group in PRESETS:
        walkers = _walkers(group, draws, seed)
        stature = float(np.mean([w.stature for w in walkers]))
        for d in ("up", "down"):
            step = float(np.mean([stair_gait(w, STAIR, d).step_time for w in walkers]))
            walk = synthetic_stair_walk(STAIR.riser, STAIR.tread, RISERS, d, step_time=step)
            motion = legs_from_walk(walk, stature=stature)
            a, b = walk.steps[1].start, walk.steps[-2].end
            knee, hip = (
                float(np.rad2deg(max(motion.angles[j.format(s)][a:b].max() for s in "lr")))
                for j in ("knee_{}", "hip_{}_flex")
            )
            swings = np.array(swing_hip_peaks(walk, motion))
            kn, hp = (KNEE_PEAK_UP, HIP_PEAK_UP) if d == "up" else (KNEE_PEAK_DOWN, HIP_PEAK_DOWN)
            # down: no published descent clearance found; 5 mm is the studies' low-clearance bound
            least = STAIR_TOE_CLEARANCE if d == "up" else DESCENT_LOW_CLEARANCE
            print(
                f"{group:12} {d:4} {stature:<10.3f} {STAIR.riser / _leg(stature):<10.3f} "
                f"{knee:<9.1f} {hip:<8.1f} "
                f"{swings[:, 1].mean():<7.1f} {swings[:, 2].mean():<5.2f} "
                f"{100 * motion.meta['edge_clearance']:<9.1f} "
                f"{trunk_flexion(motion, stature, a, b):<6.1f} knee {kn[0]:.0f}-{kn[1]:.0f}, "
                f"hip {hp[0]:.0f}-{hp[1]:.0f} deg, clearance >= "
                f"{100 * least:.1f} cm"
            )


def ramp_table(draws: int, seed: int) -> None:
    """Print the ramp figures per preset, level, up and down.

    Args:
        draws: walkers per preset.
        seed: the draws' seed.
    """
    run = RAMP_RISE / math.tan(math.radians(RAMP_DEG))
    print(
        f"\nRamp {RAMP_DEG} deg, {run:.2f} m run to the {RAMP_RISE} m platform (and "
        f"{STEEP_RAMP_DEG} deg to the same rise); norms: Tobler 1993 speed factor (capped at 1 "
        "downhill), Franz & Kram 2012 downhill cadence, downhill steps within the legs' reach"
    )
    head = (
        f"{'group':12} {'slope':6} {'speed m/s':22} {'step length m':22} "
        f"{'cadence /min':22} {'ramp time s':22}"
    )
    print(head)
    print("-" * len(head))
    for group in PRESETS:
        walkers = _walkers(group, draws, seed)
        for deg in (0.0, RAMP_DEG, -RAMP_DEG, STEEP_RAMP_DEG, -STEEP_RAMP_DEG):
            gaits = [slope_gait(w, math.radians(deg)) for w in walkers]
            run = RAMP_RISE / math.tan(math.radians(abs(deg) or RAMP_DEG))
            print(
                f"{group:12} {deg:+6.1f} {_stats([g.speed for g in gaits])} "
                f"{_stats([g.step_length for g in gaits])} "
                f"{_stats([g.cadence * 60 for g in gaits])} "
                f"{_stats([g.duration(run) for g in gaits])}"
            )


#: Walks over levels in the multi-level station: (start, goal).
LEVEL_WALKS = (
    ("stand_step", "stand_platform1"),
    ("stand_ramp", "stand_platform2"),
    ("stand_stair", "stand_mezz_rack"),
    ("stand_rack1", "stand_mezz_rack"),
    ("stand_mezz_rack", "stand_rack1"),
    ("stand_platform1", "stand_car1"),
)
SCENES = Path(__file__).resolve().parent.parent / "scenes"


def _timed(wp, start, goal, model, seed: int):
    """CPU seconds of ``plan_walk`` (this process's, so other jobs on a loaded machine do not
    count) and the walk."""
    t0 = time.process_time()
    walk = plan_walk(wp, start, goal, model, rng=seed)
    return time.process_time() - t0, walk


def _legs_alone(wp, start, goal, model, seed: int) -> float:
    """Seconds to plan the route's level legs each alone, as walks of a flat scene: a fresh
    :class:`HybridPlanner` per leg in its level's view (as ``plan_walk`` makes one per walk),
    no approach heading, no route, no crossings: the search cost of the levels' own shapes."""
    walker = model.walker or Walker()
    a, b = endpoint(wp, start, "start"), endpoint(wp, goal, "goal")
    head = walker.stature + HEAD_MARGIN
    options = PlannerOptions()
    route = level_route(wp, a, b, walker, options, step_up_limit(walker))
    legs = place_crossings(wp, route, options, head)
    rng = np.random.default_rng(seed)
    t0 = time.process_time()
    for leg in legs:
        skip = max(STANCE_TOLERANCE, options.goal_tolerance)  # as plan_level_walk's legs
        if leg.kind == "level" and float(np.hypot(*(leg.end - leg.start))) > skip:
            view = level_view(wp, leg.level, head)
            try:
                HybridPlanner(view, leg.end, model).plan(WalkRequest(leg.start), rng)
            except PlanningError:
                pass  # its time counts: the flat planner spent it too
    return time.process_time() - t0


def entry_turn_deg(walk) -> float:
    """The largest pelvis heading change (degrees) over one step among the five steps before
    a walk's first step up or down a riser or ramp and that step: how sharply it turns onto
    its first crossing (ENTRY_TURN, 60 deg, the most within one step: Patla et al. 1991)."""
    first = next((k for k, s in enumerate(walk.steps) if abs(s.foot_z - s.stance_z) > 0.01), None)
    if first is None:
        return 0.0
    steps = walk.steps[max(0, first - 5) : first + 1]
    return max(
        abs(math.degrees(math.remainder(walk.yaw[s.end] - walk.yaw[s.start], math.tau)))
        for s in steps
    )


def planning_cost(walks: int) -> None:
    """Print the planning time of walks over levels against flat walks of the same length, and
    against their own level legs planned alone as flat walks.

    Both sides are timed twice per seed, in the same way: "cold" is a seed's first plan (the
    level walk after one warm-up plan of the pair with seed 0, which builds the scene's views,
    grids, route and the legs' planners; the flat walk with its goal's distance field and
    planner built in the call, as its goal moves with each seed's length), "warm" the same
    seed's plan again (every field and planner of both kept from the first). So warm/warm
    compares the searches alone, cold/cold what a cycle's first walk of each kind pays. The
    expansions (of all searches) are the load-free figure.

    Args:
        walks: seeds per pair.
    """
    model = default_model(progress=False)
    station = load_workplace(SCENES / "multilevel_station.xml")
    flat = load_workplace(SCENES / "open_floor.xml")
    print(f"\nPlanning cost, median over {walks} seeds (CPU time; cold: a seed's first plan,")
    print("warm: the same again); flat: open floor's diagonal, same length; legs: the route's")
    print("level legs alone; exp: expansions over all searches (levels / flat), medians;")
    print("entry: the sharpest one-step turn onto the first riser or ramp, deg, max over seeds")
    head = (
        f"{'walk':38} {'route':20} {'length m':>8} {'cold ms':>13} {'ratio':>6} "
        f"{'warm ms':>13} {'ratio':>6} {'legs ms':>8} {'exp':>9} {'entry':>6}"
    )
    print(head)
    print("-" * len(head))
    worst = {"cold": 0.0, "warm": 0.0}
    for start, goal in LEVEL_WALKS:
        _timed(station, start, goal, model, 0)  # views, grids and fields of the scene, once
        _legs_alone(station, start, goal, model, 0)
        t: dict[str, list[float]] = {k: [] for k in ("lc", "lw", "fc", "fw", "legs")}
        lengths, exp, flat_exp, entry = [], [], [], []
        for seed in range(1, walks + 1):
            dt, walk = _timed(station, start, goal, model, seed)
            t["lc"].append(dt)
            t["lw"].append(_timed(station, start, goal, model, seed)[0])
            lengths.append(walk.length)
            entry.append(entry_turn_deg(walk))
            exp.append(walk.meta["expansions_all"])
            a = walk.length / (2 * math.sqrt(2))  # along the open floor's diagonal
            dt, flat_walk = _timed(flat, (-a, -a), (a, a), model, seed)
            t["fc"].append(dt)
            t["fw"].append(_timed(flat, (-a, -a), (a, a), model, seed)[0])
            flat_exp.append(flat_walk.meta["expansions_all"])
            t["legs"].append(_legs_alone(station, start, goal, model, seed))
        med = {k: 1000 * float(np.median(v)) for k, v in t.items()}
        cold, warm = med["lc"] / med["fc"], med["lw"] / med["fw"]
        worst = {"cold": max(worst["cold"], cold), "warm": max(worst["warm"], warm)}
        route = " ".join(r["kind"] for r in walk.meta["levels"]["route"])
        print(
            f"{start + ' -> ' + goal:38} {route:20} {np.median(lengths):8.2f} "
            f"{med['lc']:6.1f}/{med['fc']:<6.1f} {cold:6.2f} {med['lw']:6.1f}/{med['fw']:<6.1f} "
            f"{warm:6.2f} {med['legs']:8.1f} {np.median(exp):>4.0f}/{np.median(flat_exp):<4.0f}"
            f" {max(entry):6.0f}"
        )
    print(
        f"largest ratio to the flat walk: cold {worst['cold']:.2f}, warm {worst['warm']:.2f} "
        "(target <= 1.5)"
    )


def flat_twin(scene: Path, out: Path) -> Path:
    """The scene with its linked levels flattened, written to ``out``: every surface of a level
    reached by a step, ramp or stair (and the ramps' and stairs' own surfaces) removed, and the
    sites and bodies standing on such a level lowered by its height to the floor. The floor's
    obstacles stay as they are and those on a removed level stand where they stood, on the
    floor: a walk between the same sites goes through the same floor (the same obstacles near
    the way), with each crossing replaced by the flat distance under it.

    Args:
        scene: the MJCF scene (no external asset files).
        out: the file to write.

    Returns:
        ``out``.
    """
    graph = load_workplace(scene).levels
    linked = {lv for link in graph.links for lv in (link.lower, link.upper)} - {0}
    drop = {graph.surfaces[i].name for lv in linked for i in graph.levels[lv].surfaces}
    drop |= {graph.surfaces[i].name for link in graph.links for i in link.via}
    heights = [graph.levels[lv].height - graph.levels[0].height for lv in linked]
    tree = ET.parse(scene)
    for parent in tree.iter():
        for child in list(parent):
            if child.tag == "geom" and child.get("name") in drop:
                parent.remove(child)
    world = tree.getroot().find("worldbody")
    assert world is not None
    for child in world:  # what stands on a removed level, down to the floor
        pos = [float(v) for v in child.get("pos", "0 0 0").split()]
        if child.tag in ("body", "site") and any(abs(pos[2] - h) < 0.01 for h in heights):
            child.set("pos", f"{pos[0]} {pos[1]} 0")
    tree.write(out)
    return out


def twin_cost(walks: int) -> None:
    """Print each walk over levels against the same walk in the station's flat twin
    (:func:`flat_twin`): a flat walk of about the same length through the same floor.

    Cold: the first plan of the pair in a freshly loaded scene (levels, views, grids, fields and
    planners built in the call; the load itself not timed), on each side; warm: the same seed
    again. CPU time, median over ``walks`` seeds; expansions over all searches, medians; "per
    m": the warm ratio of milliseconds per metre walked, for a twin walk more than a quarter
    shorter or longer than the walk over levels (a mezzanine reached round its stair's foot
    whose twin walks straight onto where it stood), where the twin is no flat walk of the same
    length.

    Args:
        walks: seeds per pair.
    """
    model = default_model(progress=False)
    scene = SCENES / "multilevel_station.xml"
    print(f"\nAgainst the flat twin (levels flattened, same sites and floor), {walks} seeds:")
    head = (
        f"{'walk':38} {'length m':>11} {'cold ms':>11} {'ratio':>6} {'warm ms':>11} "
        f"{'ratio':>6} {'per m':>6} {'exp':>9}"
    )
    print(head)
    print("-" * len(head))
    worst = {"cold": 0.0, "warm": 0.0}
    with tempfile.TemporaryDirectory() as tmp:
        twin_path = flat_twin(scene, Path(tmp) / "flat_twin.xml")
        for start, goal in LEVEL_WALKS:
            rows: dict[str, list[float]] = {k: [] for k in ("lc", "lw", "tc", "tw", "ll", "tl")}
            exp: dict[str, list[int]] = {"l": [], "t": []}
            for seed in range(1, walks + 1):
                for side, path in (("l", scene), ("t", twin_path)):
                    wp = load_workplace(path)
                    clear_memos()  # cold: no footprint kept from an earlier load either
                    dt, walk = _timed(wp, start, goal, model, seed)
                    rows[side + "c"].append(dt)
                    rows[side + "w"].append(_timed(wp, start, goal, model, seed)[0])
                    rows[side + "l"].append(walk.length)
                    exp[side].append(int(walk.meta["expansions_all"]))
            med = {k: float(np.median(v)) for k, v in rows.items()}
            cold, warm = med["lc"] / med["tc"], med["lw"] / med["tw"]
            worst = {"cold": max(worst["cold"], cold), "warm": max(worst["warm"], warm)}
            print(
                f"{start + ' -> ' + goal:38} {med['ll']:5.2f}/{med['tl']:<5.2f} "
                f"{1000 * med['lc']:5.1f}/{1000 * med['tc']:<5.1f} {cold:6.2f} "
                f"{1000 * med['lw']:5.1f}/{1000 * med['tw']:<5.1f} {warm:6.2f} "
                f"{warm * med['tl'] / med['ll']:6.2f} "
                f"{np.median(exp['l']):>4.0f}/{np.median(exp['t']):<4.0f}"
                + ("  (twin not the same length)" if abs(med["tl"] / med["ll"] - 1) > 0.25 else "")
            )
    print(
        f"largest ratio to the flat twin: cold {worst['cold']:.2f}, warm {worst['warm']:.2f} "
        "(target <= 1.5)"
    )


#: What :func:`split_cost` times inside a warm walk: (owner, attribute, row).
SPLIT = (
    (HybridPlanner, "plan", "hybrid plans"),
    (levelplan, "cross_walk", "crossing walks"),
    (levelplan, "stitch", "record"),
    (levelplan, "level_meta", "record"),
    (levelplan, "_turned", "turn into a stair"),
)


@contextlib.contextmanager
def _timing(cpu: Counter, calls: Counter):
    """Add each :data:`SPLIT` function's CPU seconds and calls to ``cpu`` and ``calls`` by
    row while the block runs (the functions wrapped, then put back)."""

    def wrap(f, row):
        def timed(*args, **kwargs):
            t0 = time.process_time()
            try:
                return f(*args, **kwargs)
            finally:
                cpu[row] += time.process_time() - t0
                calls[row] += 1

        return timed

    saved = [(owner, name, getattr(owner, name)) for owner, name, _ in SPLIT]
    try:
        for (owner, name, row), (_, _, f) in zip(SPLIT, saved, strict=True):
            setattr(owner, name, wrap(f, row))
        yield
    finally:
        for owner, name, f in saved:
            setattr(owner, name, f)


def split_cost(walks: int, rounds: int = 3) -> None:
    """Print where a warm walk over levels spends its time against its flat twin's walk
    (:func:`flat_twin`): CPU ms a walk in its hybrid plans (calls a walk), crossing walks, its
    record (stitch and level meta), turns into a stair and the rest (route, level legs' set-up,
    ``plan_walk``), median over ``rounds`` rounds of seeds 1..``walks`` each planned once
    before (warm).

    Args:
        walks: seeds per pair.
        rounds: rounds over the seeds.
    """
    model = default_model(progress=False)
    scene = SCENES / "multilevel_station.xml"
    rows = ("hybrid plans", "crossing walks", "record", "turn into a stair", "rest")
    print(f"\nWhere a warm walk's time goes, CPU ms a walk (median of {rounds} rounds of {walks}")
    print("seeds); twin: the flat twin's walk, its hybrid plans alone in brackets")
    head = f"{'walk':38} {'total':>6} " + " ".join(f"{r:>17}" for r in rows) + f" {'twin':>13}"
    print(head)
    print("-" * len(head))
    with tempfile.TemporaryDirectory() as tmp:
        sides = {"l": load_workplace(scene)}
        sides["t"] = load_workplace(flat_twin(scene, Path(tmp) / "flat_twin.xml"))
        for start, goal in LEVEL_WALKS:
            for wp in sides.values():
                for seed in range(1, walks + 1):
                    plan_walk(wp, start, goal, model, rng=seed)
            got: dict[str, list[tuple[float, Counter, Counter]]] = {"l": [], "t": []}
            for _ in range(rounds):
                for side, wp in sides.items():
                    cpu, calls = Counter(), Counter()
                    with _timing(cpu, calls):
                        t0 = time.process_time()
                        for seed in range(1, walks + 1):
                            plan_walk(wp, start, goal, model, rng=seed)
                        total = time.process_time() - t0
                    got[side].append((total, cpu, calls))
            per = {  # ms a walk, median over the rounds
                side: {
                    k: 1000 / walks * float(np.median([r[1][k] if k else r[0] for r in got[side]]))
                    for k in ("", *rows[:-1])
                }
                for side in got
            }
            lv = per["l"]
            lv["rest"] = lv[""] - sum(lv[r] for r in rows[:-1])
            n = {r: got["l"][0][2][r] / walks for r in rows[:-1]}
            cells = [f"{lv[r]:6.2f}" + (f" ({n[r]:.1f})" if r in n else "") for r in rows]
            print(
                f"{start + ' -> ' + goal:38} {lv['']:6.2f} "
                + " ".join(f"{c:>17}" for c in cells)
                + f" {per['t']['']:5.2f} ({per['t']['hybrid plans']:.2f})"
            )


def main() -> None:
    """Print the tables and the planning cost."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--draws", type=int, default=400)
    ap.add_argument("--seed", type=int, default=47)
    ap.add_argument("--walks", type=int, default=20, help="seeds per walk over levels")
    ap.add_argument("--twin-only", action="store_true", help="only the flat-twin comparison")
    ap.add_argument("--split", action="store_true", help="only where a warm walk's time goes")
    args = ap.parse_args()
    if args.split:
        split_cost(args.walks)
        return
    if not args.twin_only:
        stair_table(args.draws, args.seed)
        body_table(args.draws, args.seed)
        ramp_table(args.draws, args.seed)
        if args.walks > 0:
            planning_cost(args.walks)
    if args.walks > 0:
        twin_cost(args.walks)


if __name__ == "__main__":
    main()

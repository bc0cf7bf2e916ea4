"""Ergonomic risk of simulated (or captured) motion: RULA, REBA, OWAS, the revised NIOSH lifting
equation and ISO 11226 static postures.

One concept per module: :mod:`~mjwalk.ergonomics.angles` measures the body angles the methods
read (from the humanoid's forward kinematics, or from captured joint positions);
:mod:`~mjwalk.ergonomics.rula`, :mod:`~mjwalk.ergonomics.reba`, :mod:`~mjwalk.ergonomics.owas`,
:mod:`~mjwalk.ergonomics.niosh` and :mod:`~mjwalk.ergonomics.iso11226` are the methods, pure
functions of those angles with their published tables as constants;
each is scored through one interface (:class:`~mjwalk.ergonomics.score.Score`;
:mod:`~mjwalk.ergonomics.postures`, :mod:`~mjwalk.ergonomics.lifting`) listed in
:data:`~mjwalk.ergonomics.registry.SCORES`; :mod:`~mjwalk.ergonomics.assess` scores a cycle's
timeline task by task with them (what each run keeps, without its timeline,
:mod:`~mjwalk.ergonomics.results`); :mod:`~mjwalk.ergonomics.summary` turns many runs
into the workforce's distributions; :mod:`~mjwalk.ergonomics.export` writes a timeline as BVH or
a joint-angle CSV. Angles in degrees (the methods' own unit), lengths in metres, masses in kg.
"""

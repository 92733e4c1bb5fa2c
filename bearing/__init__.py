"""Double-row tapered roller bearing (DTRB) of the axle-box (paper Eqs. 1-16).

Landed so far: parameters (:mod:`.params`), fault frequencies (:mod:`.frequencies`),
contact stiffness (:mod:`.stiffness`), Harris load-distribution integrals
(:mod:`.loaddist`) and the quasi-static equilibrium (:mod:`.quasistatic`).
The roller and cage dynamics, defects and the standalone rig follow (issue 3).
"""

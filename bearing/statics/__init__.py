"""The bearing at rest: contact stiffnesses (:mod:`.stiffness`, paper Eqs. 5-11), the
quasi-static ring equilibrium of series springs (:mod:`.quasistatic`), the dynamic model's
static start (:mod:`.equilibrium`) and Harris's load-distribution integrals (:mod:`.loaddist`).
"""

"""The bearing kernel's parts (numba), shared by every model: the plain arrays and their slots
(:mod:`.layout`), small vector algebra (:mod:`.vec`), a roller's and a cage's kinematics and
Newton-Euler equations (:mod:`.roller`, Eqs. 2, 12, 13), the contact laws (:mod:`.contact`,
Eqs. 4, 9), a roller's contacts with a ring (:mod:`.rings`) and with its pocket (:mod:`.pocket`,
Eqs. 9-11), the implicit blocks (:mod:`.blocks`), one bearing's right-hand side
(:mod:`.evaluate`, Eqs. 1-16), the implicit kick (:mod:`.implicit`), the dynamic and
quasi-dynamic sub-steps (:mod:`.step`, :mod:`.quasidynamic`), the exchange window with what
moves the rings (:mod:`.advance`), the one point where a kernel picks a model's parts
(:mod:`.dispatch`), and the DTRB's plain-numpy twin (:mod:`.numpy_twin`).
"""

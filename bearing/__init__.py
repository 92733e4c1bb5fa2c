"""Double-row tapered roller bearing dynamics with outer-ring defects (paper Eqs. 1-16).

Empty until the bearing issue lands.
"""

"""scikit-fem elasticity, free-free modes, RBE2/RBE3 interfaces, Guyan and Craig-Bampton
reduction and the reduced-body file."""

"""Load a reduced body exported by ``axlebox bodies export BODY.h5 --format exudyn --out BODY.hdf5``
into Exudyn and print its free-free frequencies.

Run: ``python docs/exudyn_example.py BODY.hdf5`` (needs ``pip install exudyn``).

The file is Exudyn's own ``FEMinterface`` data (``LoadFromFile``, HDF5 layout): mesh, full FE
mass and stiffness, the body's free-free elastic modes as the mode basis.  Exudyn's docs:
"Module: FEM" (``FEMinterface``, ``ObjectFFRFreducedOrderInterface``) and the ``ObjectFFRFreducedOrder``
item.  Units SI.  The body's modal damping and its master/output nodes (``interfaces``) are in
``fem.metaData``.
"""
import sys

import numpy as np

import exudyn as exu
from exudyn.FEM import FEMinterface, ObjectFFRFreducedOrderInterface


def load(path: str):
    """The FEMinterface, the reduced-order interface built from it, and the file's metaData."""
    fem = FEMinterface()
    fem.LoadFromFile(path)
    cms = ObjectFFRFreducedOrderInterface(fem)
    return fem, cms, fem.metaData


def add_body(mbs, fem, cms):
    """The free body at rest, no gravity, with the body file's modal damping; returns the
    item numbers of ``AddObjectFFRFreducedOrder`` (object, rigid-body node, modal node)."""
    ids = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0], initialVelocity=[0, 0, 0],
                                        initialAngularVelocity=[0, 0, 0], gravity=[0, 0, 0])
    D = exu.MatrixContainer()
    D.SetWithDenseMatrix(np.asarray(fem.metaData["dampingMatrixReduced"]), useDenseMatrix=False)
    mbs.SetObjectParameter(ids["oFFRFreducedOrder"], "dampingMatrixReduced", D)
    return ids


def frequencies_hz(cms) -> np.ndarray:
    """Free-free elastic frequencies from Exudyn's reduced mass and stiffness (Hz)."""
    M, K = np.asarray(cms.massMatrixReduced), np.asarray(cms.stiffnessMatrixReduced)
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    return np.sqrt(np.abs(w2)) / (2 * np.pi)


if __name__ == "__main__":
    fem, cms, meta = load(sys.argv[1])
    f = frequencies_hz(cms)
    print(f"{meta['body']}: {len(fem.nodes['Position'])} nodes, {len(f)} modes; {meta['source']}")
    for k, (fx, fb) in enumerate(zip(f, meta["frequencies_hz"])):
        print(f"mode {k + 1:3d}: Exudyn {fx:10.4f} Hz, body file {fb:10.4f} Hz")
    print("interfaces:", ", ".join(meta["interfaces"]))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    add_body(mbs, fem, cms)
    mbs.Assemble()
    print("assembled:", mbs.systemData.NumberOfNodes(), "nodes,", mbs.systemData.NumberOfObjects(), "objects")

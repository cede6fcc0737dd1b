#!/usr/bin/python3
"""An independent dolfinx 0.5 implementation of the Hertz sphere at its
final indentation.

What it solves. parameters/hertz_sphere.prm at t = 1 as one static
problem: a rigid sphere of radius R = 1 pressed by d = 0.01 into an elastic
block (E = 1000, Poisson ratio 0.3, 3D), the quarter model [0, 1]^3 with y
up, the contact point at the corner (0, 1, 0). Symmetry (a zero normal
displacement) on x = 0 and z = 0, a roller (u_y = 0) on the bottom y = 0,
the sides x = 1 and z = 1 free, no load. Find u in V^h minimising
1/2 (E eps(u), eps(u)) subject to, at every vertex x_i of the top face,

    u_y(x_i) <= s(x_i) = (x_i^2 + z_i^2) / (2 R) - d,

the program's nodal (lumped) contact with the obstacle's gap s along the
gap direction (0, 1, 0).

Discretisation (the program's). Q1 on the graded hexahedral mesh of
meshes/make_hertz_sphere_meshes.py: dolfinx's box of N^3 hexahedra with
its vertices moved to x = (i/N)^2, y = 1 - (1 - j/N)^2, z = (k/N)^2, the
same vertices and cells as the program's mesh file. The stiffness K is
assembled by dolfinx with the symmetry and roller dofs as identity rows
(dolfinx's Dirichlet treatment, u = 0 there).

Solver. PETSc SNES vinewtonrsls (the reduced-space active-set method for
bound constraints) with the bounds u_y,i <= s(x_i) on the y dofs of the top
face's vertices, started from u = 0 (SNES-VI projects the start onto the
bounds, so the first iterate has the vertices with s < 0 at the sphere),
line search basic (full Newton steps: the problem is a quadratic
programme), rtol = 1e-10, atol = 1e-11 on the norm of the residual
projected on the bounds, stol = 0. Each Newton iteration solves the system
of the inactive dofs, a new matrix, with the linear solver of --solver:

  gamg:  CG to rtol 1e-8 with PETSc's algebraic multigrid (smoothed
         aggregation) and the six rigid-body modes of the reduced system as
         its near null space, the best iterative set-up for elasticity;
  mumps: LU by MUMPS (KSP preonly).

PETSc options on the command line (-snes_monitor, -inner_pc_gamg_...) are
applied after these. The near null space: vinewtonrsls hands the KSP a
submatrix of K (the inactive rows and columns) that knows nothing of K's
near null space, so a python PC (RigidBodyGAMG) restricts the rigid-body
modes to the inactive set before it sets up GAMG. Without them GAMG took
twice the Krylov iterations at N = 16 (358 against 171).

How it matches the program. After the solve, per top vertex the nodal
contact force z_i = -(K u)_{y,i} (K u + sum_i z_i e_{y,i} = 0; zero off
the obstacle, where it is the linear solver's residual), the lumped
weight w_i = int_top phi_i ds and the pressure z_i / w_i; the total force
sum_i z_i (the program's total_contact_force of the quarter model) and the
number of vertices at the obstacle (u_y,i >= s_i - 1e-12 |d|). With
--profile FILE rank 0 writes x, z, contact_pressure, weight of every top
vertex (the columns of the program's contact_profile_*.csv), from which
benchmarks/run_hertz_sphere.py's profile_measures() computes the contact
radius.

Parallel: run under mpirun; dolfinx distributes the mesh; the forces,
counts and the profile are gathered to rank 0.

    mpirun -np 2 /usr/bin/python3 benchmarks/dolfinx_hertz_sphere.py --subdivisions 24 \\
        --solver gamg --profile profile.csv

Needs Debian's python3-dolfinx (0.5) and /usr/bin/python3.
"""

import argparse
import sys
import time

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem.petsc
from dolfinx import fem, mesh

YOUNG, POISSON = 1000.0, 0.3
RADIUS, INDENTATION = 1.0, 0.01


def rigid_body_modes(coordinates):
    """The six rigid-body modes of a vector field with (x, y, z) per node,
    as an (n_nodes * 3, 6) array in the node-major dof order."""
    n = len(coordinates)
    modes = np.zeros((n, 3, 6))
    x, y, z = coordinates[:, 0], coordinates[:, 1], coordinates[:, 2]
    for c in range(3):
        modes[:, c, c] = 1.0
    modes[:, 0, 3], modes[:, 1, 3] = -y, x
    modes[:, 1, 4], modes[:, 2, 4] = -z, y
    modes[:, 2, 5], modes[:, 0, 5] = -x, z
    return modes.reshape(3 * n, 6)


class RigidBodyGAMG:
    """PCGAMG on the reduced system of each Newton iteration, with the
    rigid-body modes restricted to the inactive dofs as its near null
    space (a petsc4py "python" PC: SNES-VI's submatrix does not carry K's
    near null space, and petsc4py 3.18 has no KSP pre-solve hook)."""

    def __init__(self, snes, modes, first_row):
        self.snes, self.modes, self.first_row = snes, modes, first_row
        self.gamg = None

    def setUp(self, pc):
        A, P = pc.getOperators()
        rows = self.snes.getVIInactiveSet().getIndices() - self.first_row
        vectors = []
        for k in range(self.modes.shape[1]):
            vector = P.createVecRight()
            vector.setArray(self.modes[rows, k])
            # Orthonormal, as MatNullSpace asks.
            for previous in vectors:
                vector.axpy(-vector.dot(previous), previous)
            vector.normalize()
            vectors.append(vector)
        P.setNearNullSpace(PETSc.NullSpace().create(vectors=vectors,
                                                    comm=P.getComm()))
        if self.gamg is not None:
            self.gamg.destroy()
        self.gamg = PETSc.PC().create(P.getComm())
        self.gamg.setType("gamg")
        self.gamg.setOptionsPrefix("inner_")
        self.gamg.setOperators(A, P)
        self.gamg.setFromOptions()
        self.gamg.setUp()

    def apply(self, pc, x, y):
        self.gamg.apply(x, y)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--subdivisions", type=int, default=8,
                        help="N, cells per edge of the graded cube")
    parser.add_argument("--solver", choices=("gamg", "mumps"), default="gamg",
                        help="the linear solver of each Newton iteration")
    parser.add_argument("--profile", default="",
                        help="write the top face's nodal pressures here")
    args, petsc_args = parser.parse_known_args()
    options = PETSc.Options()
    options.insertString(" ".join(petsc_args))
    if not options.hasName("snes_linesearch_type"):
        options.setValue("snes_linesearch_type", "basic")

    comm = MPI.COMM_WORLD
    n = args.subdivisions
    comm.Barrier()
    start = time.perf_counter()

    domain = mesh.create_box(comm, [np.zeros(3), np.ones(3)], [n, n, n],
                             mesh.CellType.hexahedron)
    x = domain.geometry.x
    # Exact grid values first: the vertices are at multiples of 1/N.
    grid = np.rint(x[:, :3] * n) / n
    x[:, 0] = grid[:, 0] ** 2
    x[:, 1] = 1.0 - (1.0 - grid[:, 1]) ** 2
    x[:, 2] = grid[:, 2] ** 2

    V = fem.VectorFunctionSpace(domain, ("Lagrange", 1))
    fdim = domain.topology.dim - 1

    def plane(axis, value):
        return mesh.locate_entities_boundary(
            domain, fdim, lambda p: np.isclose(p[axis], value))
    bcs = [fem.dirichletbc(PETSc.ScalarType(0), fem.locate_dofs_topological(
               V.sub(axis), fdim, plane(axis, 0.0)), V.sub(axis))
           for axis in range(3)]
    top = plane(1, 1.0)
    tags = mesh.meshtags(domain, fdim, np.sort(top).astype(np.int32),
                         np.full(len(top), 4, np.int32))
    ds = ufl.Measure("ds", domain=domain, subdomain_data=tags)

    mu = YOUNG / (2 * (1 + POISSON))
    lmbda = YOUNG * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))

    def eps(w):
        return ufl.sym(ufl.grad(w))

    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    a = fem.form(ufl.inner(lmbda * ufl.tr(eps(u)) * ufl.Identity(3)
                           + 2 * mu * eps(u), eps(v)) * ufl.dx)
    weight_form = fem.form(ufl.inner(fem.Constant(
        domain, PETSc.ScalarType((0.0, 1.0, 0.0))), v) * ds(4))
    K = fem.petsc.assemble_matrix(a, bcs=bcs)
    K.assemble()
    wvec = fem.petsc.assemble_vector(weight_form)
    wvec.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)

    index_map, bs = V.dofmap.index_map, V.dofmap.index_map_bs
    n_owned = index_map.size_local
    coordinates = V.tabulate_dof_coordinates()[:n_owned]
    nodes = np.flatnonzero(np.isclose(coordinates[:, 1], 1.0))
    local_dofs = (bs * nodes + 1).astype(np.int32)
    owned_start = index_map.local_range[0] * bs
    global_dofs = (owned_start + local_dofs).astype(PETSc.IntType)
    gap = ((coordinates[nodes, 0] ** 2 + coordinates[nodes, 2] ** 2)
           / (2 * RADIUS) - INDENTATION)
    weights = wvec.getArray(readonly=True)[local_dofs].copy()

    lower, upper = K.createVecRight(), K.createVecRight()
    lower.set(PETSc.NINFINITY)
    upper.set(PETSc.INFINITY)
    upper.setValues(global_dofs, gap)
    upper.assemble()

    def residual(snes, x, F):
        K.mult(x, F)

    def jacobian(snes, x, J, P):
        pass  # K throughout: the problem is quadratic

    F, x_vec = K.createVecLeft(), K.createVecRight()
    x_vec.set(0.0)
    snes = PETSc.SNES().create(comm)
    snes.setType("vinewtonrsls")
    snes.setFunction(residual, F)
    snes.setJacobian(jacobian, K)
    snes.setVariableBounds(lower, upper)
    snes.setTolerances(rtol=1e-10, atol=1e-11, stol=0.0, max_it=100)
    ksp = snes.getKSP()
    if args.solver == "gamg":
        ksp.setType("cg")
        ksp.setTolerances(rtol=1e-8)
        pc = ksp.getPC()
        pc.setType("python")
        pc.setPythonContext(RigidBodyGAMG(snes, rigid_body_modes(coordinates),
                                          K.getOwnershipRange()[0]))
    else:
        ksp.setType("preonly")
        ksp.getPC().setType("lu")
        ksp.getPC().setFactorSolverType("mumps")
    snes.setFromOptions()

    comm.Barrier()
    setup_time = time.perf_counter() - start
    start = time.perf_counter()
    snes.solve(None, x_vec)
    comm.Barrier()
    solve_time = time.perf_counter() - start
    reason = snes.getConvergedReason()

    R = K.createVecLeft()
    K.mult(x_vec, R)
    z = -R.getArray(readonly=True)[local_dofs]
    uy = x_vec.getArray(readonly=True)[local_dofs]
    touching = uy >= gap - 1e-12 * INDENTATION
    # Off the obstacle z_i is the linear solver's residual, not a force.
    z[~touching] = 0.0
    at_obstacle = comm.allreduce(int(touching.sum()), op=MPI.SUM)
    force = comm.allreduce(float(z.sum()), op=MPI.SUM)
    profile = comm.gather(np.column_stack([coordinates[nodes, 0],
                                           coordinates[nodes, 2],
                                           z / weights, weights]), root=0)
    if comm.rank == 0:
        if args.profile:
            np.savetxt(args.profile, np.vstack(profile), delimiter=",",
                       header="x,z,contact_pressure,weight", comments="",
                       fmt="%.12g")
        cells = domain.topology.index_map(3).size_global
        print(f"dolfinx {dolfinx.__version__}, PETSc "
              f"{'.'.join(map(str, PETSc.Sys.getVersion()))}, {comm.size} rank(s)")
        print(f"Mesh: {cells} hexahedra, {index_map.size_global * bs} "
              f"displacement dofs, {sum(len(p) for p in profile)} contact nodes")
        print(f"SNES {snes.getType()}, KSP {ksp.getType()}, linear solver "
              f"{args.solver}")
        print(f"SNES iterations: {snes.getIterationNumber()}, converged reason "
              f"{reason}, Krylov iterations {snes.getLinearSolveIterations()}")
        print(f"final contact: {at_obstacle} at the obstacle, total force = "
              f"{force:.12g}")
        print(f"set-up time: {setup_time:.4f} s, solve time: {solve_time:.4f} s")
    if reason <= 0:
        sys.exit(1)


if __name__ == "__main__":
    main()

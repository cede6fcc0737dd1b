#!/usr/bin/python3
"""An independent dolfinx 0.5 implementation of the static scene.

What it solves. The "static scene" of the benchmarks: parameters/elastic.prm
(Plasticity = false) with Subdivisions = N and End time = 0.015625, i.e. one
time step k = 1/64 from rest. The history is zero, so the step is one static
elastic contact problem: find u in U^h minimising

    1/2 (E eps(u), eps(u)) - (f, u) + sum_i w_i j(r_i),   r_i = u(x_i) . nu = -u_y(x_i),

over U^h = { v in V^h : r_i <= g at every contact node } (doc/model.md,
sections 1 and 2). Scene: the unit square in plane stress, E = 1000,
Poisson ratio 0.4; clamped on x = 0; the traction (0, -5) on y = 1; x = 1
free; no body force; contact on y = 0 (outward normal nu = (0, -1)) with a
layer of thickness g = 0.01 whose law is nonmonotone,

    p(r) = 0 (r < 0),  c1 r (0 <= r <= u1),  c1 u1 + c2 (r - u1) (r > u1),

c1 = 300, c2 = -100, u1 = 0.006, over a rigid foundation (r <= g).

Discretisation (the program's, doc/model.md section 2 "Lumping"). P1 on an
N x N grid of squares, each split by "/" (from (x_i, y_j) to (x_i+1, y_j+1):
dolfinx's DiagonalType.right). The stiffness K of the plane-stress law
sigma = lambda* tr(eps) I + 2 mu eps with lambda* = 2 lambda mu / (lambda +
2 mu) = E k / (1 - k^2), 2 mu = E / (1 + k), assembled by dolfinx; the load f
of the traction on y = 1. The contact is nodal: the contact nodes are the
vertices of y = 0 off the clamped side (the corner (0, 0) is clamped, not a
contact node), with the lumped weights w_i = int_{y=0} phi_i ds (h inside,
h/2 at x = 1). The residual and its Jacobian are

    F(u) = K u - f + sum_i w_i p(r_i) dr_i/du = K u - f - sum_i w_i p(-u_y,i) e_{y,i},
    J(u) = K + sum_i w_i p'(r_i) e_{y,i} e_{y,i}^T,

the nodal terms added on the owned dofs to the assembled vector and to the
diagonal of the assembled matrix (p' is the slope of the piece that holds
r_i, c1 at r = 0 and at r = u1 the slope of the lower piece). The rigid
limit r_i <= g is the bound u_y,i >= -g of the y dof of each contact node,
every other dof unbounded. The clamped dofs are identity rows of K with zero
right-hand side (dolfinx's usual Dirichlet treatment), so u = 0 there.

Solver. PETSc SNES, type vinewtonrsls (the reduced-space active-set
semismooth Newton method for variational inequalities with bounds), started
from u = 0, rtol = 1e-12, atol = 1e-11, stol = 0 (it stops when the
residual of the VI, projected on the bounds, is below them). Line search
"basic": full semismooth Newton steps, legacy DOLFIN's default for SNES and
what the program's active-set method does (3, 4, 6 iterations at N = 32,
64, 128). PETSc's own default for vinewtonrsls, "bt" (backtracking on
|F|^2), rejects the full step near the kinks of p and crawls with steps of
0.1: 24, 22, 19 iterations at N = 32, 64, 128 and 37 at 512, about 3 to
5 times the solve time, for the same answer (-snes_linesearch_type bt;
benchmarks/run_dolfinx_comparison.py runs both). The linear solves are KSP
preonly + LU with MUMPS (PETSc's parallel direct solver, what a dolfinx
user would take for a 2D problem of this size), on the reduced system of
the inactive dofs, so the matrix is extracted and factorised anew
(symbolic and numeric) in every Newton iteration (the program's condensed
back end factorises K once and iterates on the contact nodes). Any of
these can be overridden by PETSc options on the command line (e.g.
-snes_monitor, -pc_factor_mat_solver_type superlu_dist).

How it matches the program. After the solve, per contact node: the nodal
normal contact force z_i = (K u - f)_{y,i} (equilibrium K u = f - N^T z, so
z_i = w_i p(r_i) off the rigid limit and w_i p(r_i) + lambda_i, with the
foundation's reaction lambda_i >= 0, at it); the node is "unilateral" when
its y dof is at the bound (r_i = g), in "compliance" when r_i > 0 or
z_i > 0, else "no contact"; the total force is sum_i z_i. These are the
numbers the program prints in its run summary ("final contact: A
unilateral, B compliance, C no contact, total force = F",
ContactNodes::count_states and total_force in source/contact_nodes.cc).
Also printed: the l2 and max norms of the dof vector (the program's "Final
displacement: l2 norm ..., max norm ...", ordering-independent).

Parallel: run under mpirun; dolfinx distributes the mesh, each rank adds the
nodal terms of the contact dofs it owns (the weights are assembled and
summed onto the owners first), and the counts and the force are summed over
the ranks.

    mpirun -np 2 /usr/bin/python3 benchmarks/dolfinx_static_scene.py --subdivisions 64

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

# The scene (parameters/elastic.prm).
YOUNG, POISSON = 1000.0, 0.4
TRACTION = (0.0, -5.0)
GAP = 0.01                          # layer thickness g
C1, C2, U1 = 300.0, -100.0, 0.006   # the nonmonotone law


def law(r):
    """p(r) and the slope p'(r) of the piece that holds r (vectorised)."""
    p = np.where(r < 0, 0.0, np.where(r <= U1, C1 * r, C1 * U1 + C2 * (r - U1)))
    dp = np.where(r < 0, 0.0, np.where(r <= U1, C1, C2))
    return p, dp


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--subdivisions", type=int, default=32)
    args, petsc_args = parser.parse_known_args()
    # Remaining arguments are PETSc options (-snes_monitor, ...).
    options = PETSc.Options()
    options.insertString(" ".join(petsc_args))
    # The full semismooth Newton step (legacy DOLFIN's default for SNES);
    # PETSc's default for vinewtonrsls is bt, see the docstring.
    if not options.hasName("snes_linesearch_type"):
        options.setValue("snes_linesearch_type", "basic")
    line_search = options.getString("snes_linesearch_type")

    comm = MPI.COMM_WORLD
    n = args.subdivisions
    comm.Barrier()
    start = time.perf_counter()

    # Mesh and space.
    domain = mesh.create_unit_square(comm, n, n, mesh.CellType.triangle,
                                     diagonal=mesh.DiagonalType.right)
    V = fem.VectorFunctionSpace(domain, ("Lagrange", 1))
    tdim = domain.topology.dim
    fdim = tdim - 1

    # Boundaries: clamped x = 0, contact y = 0 (marker 2), loaded y = 1 (3).
    clamped = mesh.locate_entities_boundary(domain, fdim,
                                            lambda x: np.isclose(x[0], 0.0))
    contact = mesh.locate_entities_boundary(domain, fdim,
                                            lambda x: np.isclose(x[1], 0.0))
    loaded = mesh.locate_entities_boundary(domain, fdim,
                                           lambda x: np.isclose(x[1], 1.0))
    facets = np.concatenate([contact, loaded]).astype(np.int32)
    markers = np.concatenate([np.full(len(contact), 2, np.int32),
                              np.full(len(loaded), 3, np.int32)])
    order = np.argsort(facets)
    tags = mesh.meshtags(domain, fdim, facets[order], markers[order])
    ds = ufl.Measure("ds", domain=domain, subdomain_data=tags)

    bc = fem.dirichletbc(np.zeros(2, dtype=PETSc.ScalarType),
                         fem.locate_dofs_topological(V, fdim, clamped), V)

    # Plane stress: lambda* = 2 lambda mu / (lambda + 2 mu) = E k / (1 - k^2).
    mu = YOUNG / (2 * (1 + POISSON))
    lmbda = YOUNG * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
    lmbda_star = 2 * lmbda * mu / (lmbda + 2 * mu)

    def eps(w):
        return ufl.sym(ufl.grad(w))

    def sigma(w):
        return lmbda_star * ufl.tr(eps(w)) * ufl.Identity(2) + 2 * mu * eps(w)

    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    a = fem.form(ufl.inner(sigma(u), eps(v)) * ufl.dx)
    L = fem.form(ufl.inner(fem.Constant(domain, PETSc.ScalarType(TRACTION)), v)
                 * ds(3))
    # Lumped weights on the y dofs: int_{y=0} phi_i ds.
    weight_form = fem.form(ufl.inner(fem.Constant(domain, PETSc.ScalarType((0.0, 1.0))),
                                     v) * ds(2))

    K = fem.petsc.assemble_matrix(a, bcs=[bc])
    K.assemble()
    b = fem.petsc.assemble_vector(L)
    fem.petsc.apply_lifting(b, [a], [[bc]])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    fem.petsc.set_bc(b, [bc])
    wvec = fem.petsc.assemble_vector(weight_form)
    wvec.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)

    # Owned contact dofs: y dofs of owned vertices on y = 0 with x > 0.
    index_map, bs = V.dofmap.index_map, V.dofmap.index_map_bs
    n_owned_nodes = index_map.size_local
    coords = V.tabulate_dof_coordinates()[:n_owned_nodes]
    tol = 1e-10
    nodes = np.flatnonzero(np.isclose(coords[:, 1], 0.0, atol=tol)
                           & (coords[:, 0] > tol))
    local_dofs = (bs * nodes + 1).astype(np.int32)
    owned_start = index_map.local_range[0] * bs
    global_dofs = (owned_start + local_dofs).astype(PETSc.IntType)
    weights = wvec.getArray(readonly=True)[local_dofs].copy()

    # Bounds: u_y >= -g at the contact nodes, everything else free.
    lower = K.createVecRight()
    upper = K.createVecRight()
    lower.set(PETSc.NINFINITY)
    upper.set(PETSc.INFINITY)
    lower.setValues(global_dofs, np.full(len(global_dofs), -GAP))
    lower.assemble()

    def residual(snes, x, F):
        K.mult(x, F)
        F.axpy(-1.0, b)
        r = -x.getArray(readonly=True)[local_dofs]
        p, _ = law(r)
        # dr/du_y = -1: the layer pushes the body up.
        F.setValues(global_dofs, -weights * p, addv=PETSc.InsertMode.ADD_VALUES)
        F.assemble()

    diagonal = K.createVecRight()

    def jacobian(snes, x, J, P):
        K.copy(J, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        r = -x.getArray(readonly=True)[local_dofs]
        _, dp = law(r)
        diagonal.set(0.0)
        diagonal.setValues(global_dofs, weights * dp)
        diagonal.assemble()
        J.setDiagonal(diagonal, addv=PETSc.InsertMode.ADD_VALUES)

    J = K.duplicate(copy=True)
    F = K.createVecLeft()
    x = K.createVecRight()
    x.set(0.0)

    snes = PETSc.SNES().create(comm)
    snes.setType("vinewtonrsls")
    snes.setFunction(residual, F)
    snes.setJacobian(jacobian, J)
    snes.setVariableBounds(lower, upper)
    snes.setTolerances(rtol=1e-12, atol=1e-11, stol=0.0, max_it=50)
    ksp = snes.getKSP()
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("lu")
    pc.setFactorSolverType("mumps")
    snes.setFromOptions()

    comm.Barrier()
    setup_time = time.perf_counter() - start
    start = time.perf_counter()
    snes.solve(None, x)
    comm.Barrier()
    solve_time = time.perf_counter() - start

    reason = snes.getConvergedReason()
    iterations = snes.getIterationNumber()

    # The program's report: z_i = (K u - f)_y,i, states, sum of z_i.
    R = K.createVecLeft()
    K.mult(x, R)
    R.axpy(-1.0, b)
    z = R.getArray(readonly=True)[local_dofs]
    r = -x.getArray(readonly=True)[local_dofs]
    rigid = r >= GAP - 1e-12
    compliance = ~rigid & ((r > 0) | (z > 0))
    counts = np.array([rigid.sum(), compliance.sum(), (~rigid & ~compliance).sum()])
    counts = comm.allreduce(counts, op=MPI.SUM)
    force = comm.allreduce(float(z.sum()), op=MPI.SUM)
    # The reaction of the foundation (z - w p at the rigid nodes).
    p, _ = law(r)
    reaction = comm.allreduce(float((z - weights * p)[rigid].sum()), op=MPI.SUM)
    n_contact = comm.allreduce(len(local_dofs), op=MPI.SUM)
    l2 = x.norm(PETSc.NormType.NORM_2)
    linf = x.norm(PETSc.NormType.NORM_INFINITY)

    if comm.rank == 0:
        print(f"dolfinx {dolfinx.__version__}, PETSc "
              f"{'.'.join(map(str, PETSc.Sys.getVersion()))}, {comm.size} rank(s)")
        print(f"Mesh: {domain.topology.index_map(tdim).size_global} triangles, "
              f"{index_map.size_global * bs} displacement dofs, {n_contact} contact nodes")
        print(f"SNES {snes.getType()}, KSP {ksp.getType()}, PC {pc.getType()} "
              f"({pc.getFactorSolverType()}), line search {line_search}")
        print(f"SNES iterations: {iterations}, converged reason {reason}, "
              f"linear solves {snes.getLinearSolveIterations()}")
        print(f"final contact: {counts[0]} unilateral, {counts[1]} compliance, "
              f"{counts[2]} no contact, total force = {force:.12g}")
        print(f"foundation reaction at the rigid nodes: {reaction:.12g}")
        print(f"Final displacement: l2 norm {l2:.10g}, max norm {linf:.10g}")
        print(f"set-up time: {setup_time:.4f} s, solve time: {solve_time:.4f} s")
    if reason <= 0:
        sys.exit(1)


if __name__ == "__main__":
    main()

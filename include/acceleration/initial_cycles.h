#ifndef viscoplastic_contact_initial_cycles_h
#define viscoplastic_contact_initial_cycles_h

namespace ViscoContact
{
  template <int dim>
  class ViscoplasticContact;

  // @sect3{Initial cycles: nested iteration on the first step}
  //
  // (doc/adaptivity.md, "Initial cycles".) Step 1 is solved on the mesh the
  // parameter file's Initial cycles coarsen, then again on each finer mesh
  // from the state carried over (mesh/mesh_adaptation.h), so that the
  // active-set iteration on the final mesh starts next to its end. The
  // function reads and changes the state of a ViscoplasticContact (the
  // problem), whose friend this class is.
  template <int dim>
  class InitialCycles
  {
  public:
    // Leaves the problem on its final mesh with the state carried over to it
    // and the external load of step 1: the start of run()'s step 1.
    static void
    solve(ViscoplasticContact<dim> &problem);
  };
} // namespace ViscoContact

#endif

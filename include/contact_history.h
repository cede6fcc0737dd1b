#ifndef viscoplastic_contact_contact_history_h
#define viscoplastic_contact_contact_history_h

#include <deal.II/base/array_view.h>

#include <deal.II/lac/affine_constraints.h>

#include "back_ends/linear_algebra.h"

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  class ContactNodes;
  template <int dim>
  class ContactSet;

  // @sect3{The explicit history of a contact law}
  //
  // A law with a history (the memory term, normal_memory.h; the bonding of
  // adhesion, bonding_field.h) keeps a few variables per contact node and
  // takes them explicitly in each step, as the paper's scheme takes the
  // viscoplastic history: from the variables and the penetrations r of
  // the last accepted step it gives the nodes their law for the step being
  // solved (start_step(): a memory pressure, an adhesive scale), and
  // accept_step() keeps the variables of the step that was accepted. A
  // repeated attempt of a step (a cut, a rejected adaptive step) calls
  // start_step() again with its own length.
  //
  // The variables travel as nodal fields in the displacement layout, for
  // checkpoints and for transfers to a new mesh; this class writes and reads
  // them once for every law.
  class ContactHistory
  {
  public:
    virtual ~ContactHistory() = default;

    // Whether any zone has the law.
    virtual bool
    active() const = 0;
    // The variables per node, and the number of nodes (of this rank).
    virtual unsigned int
    n_variables() const = 0;
    virtual unsigned int
    n_nodes() const = 0;
    // Variable v of node i at the last accepted step, and setting it (a
    // restored checkpoint, a transfer).
    virtual double
    variable(const unsigned int i, const unsigned int v) const = 0;
    virtual void
    set_variable(const unsigned int i, const unsigned int v, const double x)
      = 0;

    // The nodes' law for a step of length k from the history at its start,
    // and the history of the accepted step from the nodes' state (their
    // penetrations r, their forces and slips; after set-up: the initial
    // state, for the first step).
    virtual void
    start_step(const double k, ContactNodes &nodes)
      = 0;
    virtual void
    accept_step(const ContactNodes &nodes)
      = 0;
    // The nodes' law of the last accepted step (after a restored
    // checkpoint or a transfer, before the next step).
    virtual void
    apply_accepted(ContactNodes &nodes) const = 0;

    // The variables as nodal fields in the displacement layout (variable v
    // of a node at its dof v % dim of field v / dim, zero elsewhere, with
    // the hanging-node constraints applied and the ghosts imported); and
    // back from such fields at the nodes of this rank. None if inactive.
    template <int dim>
    std::vector<VectorType>
    nodal_fields(const ContactSet<dim>           &contact,
                 const VectorType                &layout,
                 const AffineConstraints<double> &hanging_constraints) const;
    template <int dim>
    void
    set_from_nodal_fields(const ContactSet<dim>             &contact,
                          const ArrayView<const VectorType> &fields);
    unsigned int
    n_nodal_fields(const unsigned int dim) const;
  };

  // @sect3{A history of one variable per node}
  //
  // The common form of a law whose history is one number per contact node
  // (the worn depth, the reached cohesive opening): zero at the start, in
  // the zones that have the law. The nodes get the values of the last
  // accepted step for every step (apply()); what the law adds after a step
  // is its own accept_step().
  class NodeValueHistory : public ContactHistory
  {
  public:
    // Whether each zone has the law, and the zone of every contact node of
    // this rank; every value is zero.
    void
    reinit(const std::vector<bool>         &zone_has_law,
           const std::vector<unsigned int> &node_zones);

    bool
    active() const override;
    unsigned int
    n_variables() const override;
    unsigned int
    n_nodes() const override;
    double
    variable(const unsigned int i, const unsigned int v) const override;
    void
    set_variable(const unsigned int i,
                 const unsigned int v,
                 const double       x) override;

    // The values on the nodes; the step's own length does not enter.
    void
    start_step(const double k, ContactNodes &nodes) override;
    void
    apply_accepted(ContactNodes &nodes) const override;

  protected:
    // Whether node i's zone has the law, and its zone.
    bool
    has_law(const unsigned int i) const;
    unsigned int
    zone(const unsigned int i) const;
    // The values of the last accepted step given to the nodes.
    virtual void
    apply(ContactNodes &nodes) const = 0;

    std::vector<double> values;

  private:
    std::vector<bool>         zone_has_law;
    std::vector<unsigned int> zones;
    bool                      any = false;
  };

  // The nodal fields of several histories, one after the other (with their
  // ghosts: the vector is filled without reallocation, since a copy of a
  // distributed vector drops its ghost values); and the histories restored
  // from such fields, each then applied to the nodes (the active ones:
  // those that made fields).
  template <int dim, typename Histories>
  std::vector<VectorType>
  nodal_fields_of(const Histories                 &histories,
                  const ContactSet<dim>           &contact,
                  const VectorType                &layout,
                  const AffineConstraints<double> &hanging_constraints)
  {
    std::size_t n = 0;
    for (const ContactHistory *history : histories)
      n += history->n_nodal_fields(dim);
    std::vector<VectorType> fields;
    fields.reserve(n);
    for (const ContactHistory *history : histories)
      for (VectorType &field :
           history->nodal_fields(contact, layout, hanging_constraints))
        fields.emplace_back(std::move(field));
    return fields;
  }

  template <int dim, typename Histories>
  void
  restore_from_nodal_fields(const Histories               &histories,
                            ContactSet<dim>               &contact,
                            const std::vector<VectorType> &fields)
  {
    auto field = fields.begin();
    for (ContactHistory *history : histories)
      if (history->active())
        {
          const unsigned int n = history->n_nodal_fields(dim);
          history->set_from_nodal_fields(contact,
                                         make_array_view(field, field + n));
          history->apply_accepted(contact);
          field += n;
        }
  }
} // namespace ViscoContact

#endif

#ifndef viscoplastic_contact_contact_histories_h
#define viscoplastic_contact_contact_histories_h

#include "archard_wear.h"
#include "bonding_field.h"
#include "cohesive_damage.h"
#include "contact_history.h"
#include "normal_memory.h"

#include <array>

namespace ViscoContact
{
  // @sect3{The laws with a history of the contact zones}
  //
  // One object per law (contact_history.h), each active where a zone has
  // the law: the memory term of the normal law, the bonding of adhesion,
  // Archard's wear and the damage of a cohesive interface. all() lists them
  // for what every one gets: a start and an end of each step, checkpoints,
  // transfers to a new mesh, the restore of a failed step.
  struct ContactHistories
  {
    NormalMemory   memory;
    BondingField   bonding;
    ArchardWear    wear;
    CohesiveDamage damage;

    std::array<ContactHistory *, 4>
    all()
    {
      return {{&memory, &bonding, &wear, &damage}};
    }
    std::array<const ContactHistory *, 4>
    all() const
    {
      return {{&memory, &bonding, &wear, &damage}};
    }
  };
} // namespace ViscoContact

#endif

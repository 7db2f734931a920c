#ifndef dynamic_contact_well_posedness_report_h
#define dynamic_contact_well_posedness_report_h

#include <dynamic_contact/parameters/parameters.h>

#include <string>

namespace DynamicContact
{
  /**
   * The report of the scene @p parameters in @p dim dimensions
   * (WellPosedness::report()), or "" where the friction coefficient does
   * not depend on the slip rate (Friction/Law none or constant): the
   * conditions concern the weakening.
   */
  template <int dim>
  std::string
  well_posedness_report(const RunParameters &parameters);
} // namespace DynamicContact

#endif

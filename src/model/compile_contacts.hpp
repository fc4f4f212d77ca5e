#pragma once
// The ground's contacts and the boom's backstop as elements (model/contact_elements.hpp), and the
// envelope a run is checked against (model/envelope.hpp).

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Adds the contact elements of `ground.surface` and `crane.backstop`, and fills model.envelope.
/// Throws SceneError for a backstop on a hinge it cannot act on.
void compileContacts(Model& model, const Scene& scene);

}  // namespace cranesim

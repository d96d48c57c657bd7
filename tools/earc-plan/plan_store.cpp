#include "plan_store.hpp"

#include "earc/io/input_error.hpp"

namespace earc {

std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db) {
  if (method != Method::Earc) return nullptr;
  throw InputError(db, "--db", "the experience store is not available in this build yet");
}

}  // namespace earc

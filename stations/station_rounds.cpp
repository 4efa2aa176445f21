#include "station_rounds.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <type_traits>

#include "skyfuse/registry/dispatch.hpp"
#include "station.hpp"

namespace skyfuse::station {

// The filter part and the model pick the fusion; the sensor is the sensing's business.
int run_station_rounds(const StationOptions& options, const RunPlan& plan, const StationConfig& me,
                       std::unique_ptr<AnyStationSensing> sensing) {
  int code = options::kExitError;
  bool found = false;
  visit_filter(plan.scenario.filter, [&]<typename Filter>(std::type_identity<Filter>) {
    found = visit_model_kind<MotionModels>(
        plan.scenario.filter.motion_model.kind, [&]<typename Model>(std::type_identity<Model>) {
          // The loader gives a filter only the models it runs on.
          if constexpr (Filter::kMotionModel.empty() || Filter::kMotionModel == Model::kKind) {
            using Fusion = typename StationFusionOf<Filter, Model>::type;
            using Sensing = typename Fusion::Sensing;
            auto* typed = dynamic_cast<Sensing*>(sensing.get());
            if (typed == nullptr) {
              throw std::logic_error(
                  fmt::format("station {}: its sensing was not made for filter {} on {}", me.id,
                              Filter::kKind, Model::kKind));
            }
            sensing.release();
            code =
                detail::run_station_of<Fusion>(options, plan, me, std::unique_ptr<Sensing>(typed));
          } else {
            throw std::logic_error(
                fmt::format("filter {} on motion model {}", Filter::kKind, Model::kKind));
          }
        });
  });
  if (!found) {
    throw std::logic_error(
        fmt::format("unregistered motion model {}", plan.scenario.filter.motion_model.kind));
  }
  return code;
}

}  // namespace skyfuse::station

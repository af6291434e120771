#pragma once

#include <memory>
#include <string>

namespace fesd {

class Discretization;
struct OcpDefinition;
struct DiscretizationOptions;

/// A nonsmooth dynamic system the FESD machinery can discretise: a projected dynamical system
/// (DcsModel) or a Filippov system in Stewart's form (StewartModel). Integrator and OCP solver
/// only see this interface; each model kind builds its own discretisation.
class DynamicsModel {
 public:
  virtual ~DynamicsModel() = default;

  virtual int stateSize() const = 0;
  virtual int controlSize() const = 0;
  virtual const std::string& name() const = 0;

  /// The FESD (or standard) discretisation of an OCP whose model is this one.
  virtual std::unique_ptr<Discretization> discretize(
      const OcpDefinition& ocp, const DiscretizationOptions& options) const = 0;
};

}  // namespace fesd

// A TraceScene on the tracer's device: the compacted bottom levels of the scene's meshes and the
// top level over its instances. Holds the device, so it may outlive the tracer that built it.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "vk/acceleration_structure.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh::vk {

class OneTimeCommands;
class VulkanDevice;

class AccelerationScene final : public TraceScene {
 public:
  // Throws vk::SystemError on a failing call, lgh::Error(TooLarge) past 2^32 vertices or indices.
  // Built with the frames' one-time commands (VulkanDevice::oneTimeCommands), or with `oneTime`
  // (one of the builds made ahead, held until the build's GPU work is waited for).
  static std::unique_ptr<AccelerationScene> build(std::shared_ptr<const VulkanDevice> device,
                                                  const Scene& scene);
  static std::unique_ptr<AccelerationScene> build(std::shared_ptr<const VulkanDevice> device,
                                                  const Scene& scene, OneTimeCommands& oneTime);
  // Hands the structures to the device's deferred release: a trace in flight may still read them.
  ~AccelerationScene() override;
  AccelerationScene(const AccelerationScene&) = delete;
  AccelerationScene& operator=(const AccelerationScene&) = delete;

  std::size_t gpuBytes() const override;
  double buildGpuMs() const override { return buildGpuMsReader()(); }
  std::function<double()> buildGpuMsReader() const override;
  std::size_t triangleCount() const override { return triangleCount_; }

  const VulkanDevice& device() const { return *device_; }
  ::vk::AccelerationStructureKHR topLevel() const { return topLevel_.handle(); }

 private:
  AccelerationScene(std::shared_ptr<const VulkanDevice> device,
                    std::vector<AccelerationStructure> bottomLevels,
                    AccelerationStructure topLevel);

  std::shared_ptr<const VulkanDevice> device_;
  std::vector<AccelerationStructure> bottomLevels_;
  AccelerationStructure topLevel_;
  // The build's GPU ms, written when its submission is retired; < 0 until then.
  std::shared_ptr<double> buildGpuMs_ = std::make_shared<double>(-1.0);
  std::size_t triangleCount_ = 0;
  OneTimeCommands* oneTime_ = nullptr;  // what its build was submitted with
};

}  // namespace lgh::vk

#include "vk/trace_batch.hpp"

#include "vk/exported_semaphores.hpp"
#include "vk/trace_barriers.hpp"
#include "vk/trace_submissions.hpp"

namespace lgh::vk {
namespace {

void record(const TraceSubmissions& submissions, std::uint32_t slot, std::uint32_t queueFamily,
            const TraceBatch& batch) {
  const ::vk::raii::CommandBuffer& commands = submissions.commands(slot);
  const bool zeroes = batch.zeroedBytes > 0;
  const TraceBarrierScope scope{.traceStage = batch.recorder->stage(),
                                .transport = batch.transport,
                                .queueFamily = queueFamily,
                                .buffers = batch.buffers,
                                .fillsFirst = zeroes};
  commands.begin({.flags = ::vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  submissions.timestamps().begin(commands, slot);
  recordBarriersBeforeTrace(commands, scope);
  if (zeroes) {
    commands.fillBuffer(batch.zeroed, 0, batch.zeroedBytes, 0);
    recordFillBeforeTrace(commands, scope);
  }
  batch.recorder->record(commands, batch.set, batch.constants, batch.launch);
  recordBarriersAfterTrace(commands, scope);
  submissions.timestamps().end(commands, slot);
  commands.end();
}

}  // namespace

void submitTraceBatch(TraceSubmissions& submissions, std::uint32_t slot, std::uint32_t queueFamily,
                      const TraceBatch& batch, const ExportedSemaphores* semaphores) {
  record(submissions, slot, queueFamily, batch);
  submissions.submit(slot, semaphores != nullptr ? semaphores->glDone() : ::vk::Semaphore{},
                     ::vk::PipelineStageFlagBits::eAllCommands,
                     semaphores != nullptr ? semaphores->vkDone() : ::vk::Semaphore{});
}

}  // namespace lgh::vk

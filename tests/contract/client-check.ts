// The TypeScript client generated from proto/openapi.json (by @hey-api/openapi-ts, into
// ./generated), used as a client would use it. tsc --strict compiles it: the camera's fields
// must survive generation, per camera type (the @ts-expect-error lines must be errors). Then it
// runs against a real lghd at LGHD_URL: a render with an explicit camera, and a job submitted,
// polled and fetched.
import { createClient } from "./generated/client";
import { getJob, getJobResult, render, submitJob } from "./generated/sdk.gen";
import type {
  BenchmarkResult,
  Camera,
  JobRequest,
  JobStatus,
  RenderRequest,
  RenderResponse,
} from "./generated/types.gen";

declare const process: { env: Record<string, string | undefined>; exitCode?: number };

// --- Types ---------------------------------------------------------------------------------------

const lookAt: Camera = {
  type: "look_at",
  position: [0, 2, 5],
  target: [0, 0.5, 0],
  up: [0, 1, 0],
  yfov: 40,
  znear: 0,
  zfar: 0,
};
const auto: Camera = { type: "auto", view_direction: [1, 0.6, 1.4], margin: 1.2, yfov: 45 };
const gltf: Camera = { type: "gltf", index: 0 };
// @ts-expect-error: a look_at camera has no view_direction
const mixed: Camera = { type: "look_at", view_direction: [1, 0, 0] };
// @ts-expect-error: a position is [x, y, z]
const short: Camera = { type: "look_at", position: [0, 1] };
// @ts-expect-error: there is no orbit camera
const orbit: Camera = { type: "orbit" };
// @ts-expect-error: a job's kind selects its members: a render job has no iterations
const renderJobWithIterations: JobRequest = { kind: "render", iterations: 3 };
const benchmarkJob: JobRequest = {
  kind: "benchmark",
  request: { output: { width: 32, height: 32 } },
  warmup: 0,
  iterations: 2,
};
void [gltf, mixed, short, orbit, renderJobWithIterations];

// --- Against a real daemon -----------------------------------------------------------------------

function check(condition: boolean, what: string): void {
  if (!condition) throw new Error("client check failed: " + what);
}

const pngSignature = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

function isPng(bytes: Uint8Array): boolean {
  return pngSignature.every((value, i) => bytes[i] === value);
}

async function waitForJob(client: ReturnType<typeof createClient>, id: string): Promise<JobStatus> {
  for (let attempt = 0; attempt < 600; ++attempt) {
    const { data, error } = await getJob({ client, path: { id } });
    check(error === undefined && data !== undefined, "GET /v1/jobs/{id}: " + JSON.stringify(error));
    const status = data as JobStatus;
    check(status.progress.done <= status.progress.total, "progress within its total");
    if (status.status !== "queued" && status.status !== "running") return status;
    await new Promise((resolve) => setTimeout(resolve, 100));
  }
  throw new Error("the job did not finish within 60 s");
}

async function main(): Promise<void> {
  const baseUrl = process.env.LGHD_URL;
  check(baseUrl !== undefined, "LGHD_URL is set");
  const client = createClient({ baseUrl });

  // A render with the look_at camera, answered as JSON.
  const request: RenderRequest = { camera: lookAt, output: { width: 48, height: 32 } };
  const rendered = await render({ client, body: request, headers: { Accept: "application/json" } });
  check(rendered.response.status === 200, "POST /v1/render: " + JSON.stringify(rendered.error));
  const answer = rendered.data as RenderResponse;
  check(answer.width === 48 && answer.height === 32, "the JSON answer's size");
  check(answer.mime === "image/png" && answer.image.startsWith("iVBORw0KGgo"), "a base64 PNG");
  check(answer.timings.some((row) => row.pass === "total"), "the timing table");

  // A render job with the auto camera: 202 + Location, polled, then the PNG.
  const submitted = await submitJob({
    client,
    body: { kind: "render", request: { camera: auto, output: { width: 40, height: 30 } } },
  });
  check(submitted.response.status === 202, "POST /v1/jobs: " + JSON.stringify(submitted.error));
  const job = submitted.data as JobStatus;
  check(submitted.response.headers.get("Location") === job.href, "Location names the job");
  const done = await waitForJob(client, job.id);
  check(done.status === "succeeded", "the render job succeeded: " + JSON.stringify(done.error));
  const result = await getJobResult({ client, path: { id: job.id }, parseAs: "arrayBuffer" });
  check(result.response.status === 200, "GET /v1/jobs/{id}/result");
  check(isPng(new Uint8Array(result.data as unknown as ArrayBuffer)), "the result is a PNG");

  // A benchmark job: its JSON result.
  const bench = await submitJob({ client, body: benchmarkJob });
  const benchDone = await waitForJob(client, (bench.data as JobStatus).id);
  check(benchDone.status === "succeeded", "the benchmark job succeeded: " + JSON.stringify(benchDone.error));
  const benchResult = await getJobResult({ client, path: { id: benchDone.id } });
  const timings = benchResult.data as BenchmarkResult;
  check(timings.kind === "benchmark" && timings.total_ms.length === 2, "two timed renders");
  console.log("client check: render, render job and benchmark job through the generated client");
}

main().catch((error: unknown) => {
  console.error(error);
  process.exitCode = 1;
});

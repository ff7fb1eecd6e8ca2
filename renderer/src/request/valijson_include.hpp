// valijson, configured once: it reports schema problems by exception instead of abort().
// Every translation unit of ours that uses valijson includes it through this header, so the
// inline functions it defines are the same everywhere (ODR).
#pragma once

#include <stdexcept>  // valijson's exceptions.hpp includes it inside its namespace otherwise

#ifndef VALIJSON_USE_EXCEPTIONS
#define VALIJSON_USE_EXCEPTIONS 1
#endif

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

// Guarded: the component boundary's one catch (ocean/Ocean.h: errors are values). Internal header.
#pragma once

#include "engine/gl/Shader.h"
#include "ocean/Ocean.h"

#include <new>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {

/// Runs `body`, turning what it throws into a Status (ErrorCode by the exception's type; the message as
/// thrown, naming the field or the program): the component boundary's one catch.
template <class Body>
Status guarded(Body&& body) noexcept {
    try {
        body();
        return {};
    } catch (const std::invalid_argument& e) {
        return {ErrorCode::InvalidArgument, e.what()};
    } catch (const std::out_of_range& e) {
        return {ErrorCode::InvalidArgument, e.what()};
    } catch (const gl::ShaderError& e) {
        return {ErrorCode::GpuFailure, e.what()};
    } catch (const std::bad_alloc&) {
        return {ErrorCode::OutOfMemory, "out of memory"};
    } catch (const std::exception& e) {
        return {ErrorCode::Internal, e.what()};
    } catch (...) {
        return {ErrorCode::Internal, "unknown exception"};
    }
}

/// Throws std::invalid_argument "WHAT must be finite" unless `finite`.
inline void requireFinite(bool finite, const std::string& what) {
    if (!finite)
        throw std::invalid_argument(what + " must be finite");
}

} // namespace pacifica::ocean

// The checks every request passes (web/security.hpp): Host, Origin, Content-Type, token.
#include "web/security.hpp"

#include <gtest/gtest.h>

namespace armctl::web {
namespace {

RequestFacts get_from(std::string_view host) { return RequestFacts{"GET", host, {}, {}, false, {}, {}, {}}; }

TEST(Security, HostMustNameThisServer) {
  const SecurityPolicy p{"127.0.0.1", 8080, ""};
  EXPECT_FALSE(check_request(p, get_from("127.0.0.1:8080")));
  EXPECT_FALSE(check_request(p, get_from("localhost:8080")));
  EXPECT_FALSE(check_request(p, get_from("LOCALHOST:8080")));
  EXPECT_FALSE(check_request(p, get_from("[::1]:8080")));
  auto r = check_request(p, get_from("evil.example:8080"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_NE(r->message.find("Host 'evil.example:8080' is not this server"), std::string::npos) << r->message;
  EXPECT_TRUE(check_request(p, get_from("127.0.0.1:8081")));
  EXPECT_TRUE(check_request(p, get_from("127.0.0.1")));  // port 80
  EXPECT_TRUE(check_request(p, RequestFacts{"GET", {}, {}, {}, false, {}, {}, {}}));
}

TEST(Security, EveryAddressTakesOnlyAddressLiterals) {
  const SecurityPolicy p{"0.0.0.0", 9000, "secret-token"};
  RequestFacts r = get_from("192.168.1.7:9000");
  r.authorization = "Bearer secret-token";
  EXPECT_FALSE(check_request(p, r));
  r.host = "rebound.example:9000";
  EXPECT_EQ(check_request(p, r)->status, 403);
}

TEST(Security, WithoutAnOriginARefererMustBeThisServer) {
  const SecurityPolicy p{"127.0.0.1", 8080, ""};
  RequestFacts r{"POST", "127.0.0.1:8080", {}, "application/json", true, {}, {}, {}};
  EXPECT_FALSE(check_request(p, r));  // curl, scripts: neither header
  r.referer = "http://127.0.0.1:8080/";
  EXPECT_FALSE(check_request(p, r));
  r.referer = "http://127.0.0.1:8080?token=x";
  EXPECT_FALSE(check_request(p, r));
  for (const char* other : {"http://evil.example/", "http://127.0.0.1:8080.evil.example/", "http://127.0.0.1:80/"}) {
    r.referer = other;
    auto refused = check_request(p, r);
    ASSERT_TRUE(refused) << other;
    EXPECT_EQ(refused->status, 403);
    EXPECT_NE(refused->message.find("Referer"), std::string::npos) << refused->message;
  }
  r.method = "GET";  // reading is allowed from anywhere the Host and Origin checks allow
  EXPECT_FALSE(check_request(p, r));
}

TEST(Security, OriginMustBeThisServer) {
  const SecurityPolicy p{"127.0.0.1", 8080, ""};
  RequestFacts r{"POST", "127.0.0.1:8080", "http://127.0.0.1:8080", "application/json", true, {}, {}, {}};
  EXPECT_FALSE(check_request(p, r));
  r.origin = "http://evil.example";
  auto refused = check_request(p, r);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 403);
  EXPECT_NE(refused->message.find("Origin 'http://evil.example' is not allowed"), std::string::npos);
  r.origin = "null";
  EXPECT_EQ(check_request(p, r)->status, 403);
  r.origin = "https://127.0.0.1:8080";
  EXPECT_EQ(check_request(p, r)->status, 403);
}

TEST(Security, BodiesMustBeJson) {
  const SecurityPolicy p{"127.0.0.1", 8080, ""};
  RequestFacts r{"POST", "127.0.0.1:8080", {}, "text/plain", true, {}, {}, {}};
  EXPECT_EQ(check_request(p, r)->status, 415);
  r.content_type = "application/x-www-form-urlencoded";
  EXPECT_EQ(check_request(p, r)->status, 415);
  r.content_type = {};
  EXPECT_EQ(check_request(p, r)->status, 415);
  r.content_type = "application/json; charset=utf-8";
  EXPECT_FALSE(check_request(p, r));
  r.content_type = {};
  r.has_body = false;  // a POST without a body (curl -X POST) needs no type
  EXPECT_FALSE(check_request(p, r));
}

TEST(Security, TokenByHeaderOrParameter) {
  const SecurityPolicy p{"127.0.0.1", 8080, "0123456789abcdef"};
  RequestFacts r = get_from("127.0.0.1:8080");
  auto refused = check_request(p, r);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 401);
  r.authorization = "Bearer 0123456789abcdef";
  EXPECT_FALSE(check_request(p, r));
  r.authorization = "Bearer 0123456789abcdeF";
  EXPECT_EQ(check_request(p, r)->status, 401);
  r.authorization = {};
  r.token_parameter = "0123456789abcdef";
  EXPECT_FALSE(check_request(p, r));
  r.token_parameter = "0123456789abcde";
  EXPECT_EQ(check_request(p, r)->status, 401);
}

TEST(Security, LoopbackAndTokens) {
  EXPECT_TRUE(is_loopback("127.0.0.1"));
  EXPECT_TRUE(is_loopback("127.1.2.3"));
  EXPECT_TRUE(is_loopback("::1"));
  EXPECT_TRUE(is_loopback("localhost"));
  EXPECT_FALSE(is_loopback("0.0.0.0"));
  EXPECT_FALSE(is_loopback("192.168.0.2"));
  const std::string a = make_token(), b = make_token();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(a, b);
}

}  // namespace
}  // namespace armctl::web

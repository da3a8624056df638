// Regression: HeadAttractor::update reproduces, to 1e-9, the trajectories recorded from the implementation
// of commit f7cfe83 (one 185-line update()) before it was split into named steps. The scenarios drive every
// behaviour, saccades, habituation, the idle timeout, the tilt and bad input through a simulated servo.
//
// Regenerate the table ONLY for an intended change of behaviour:
//   BIOVISION_PRINT_GOLDEN=1 devel/lib/biovision_attractor/test_head_attractor_golden
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_attractor/head_attractor.hpp"

using namespace biovision_attractor;

namespace
{
constexpr double kDt = 0.1;                      // control period [s]
constexpr double kHalfFov = 21.5 * M_PI / 180;  // [rad]
constexpr double kServoStep = 0.3;               // [rad] per period (3 rad/s)
constexpr int kSteps = 400;                      // per scenario (40 s)
constexpr int kSampleEvery = 20;                 // steps between recorded samples
constexpr double kTolerance = 1e-9;

double deg(double d)
{
  return d * M_PI / 180;
}

double servo(double joint, double command)
{
  return joint + std::clamp(command - joint, -kServoStep, kServoStep);
}

// A deterministic generator independent of the standard library's distributions (their output may
// differ between implementations; the golden values must not).
class Lcg
{
public:
  explicit Lcg(uint64_t seed) : state_(seed) {}
  double unit()  // [0, 1)
  {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

private:
  uint64_t state_;
};

struct Object
{
  double pan, tilt, peak;
};

std::vector<SeenRegion> look(const std::vector<Object>& objects, double pan)
{
  std::vector<SeenRegion> seen;
  for (const Object& o : objects)
    if (std::abs(o.pan - pan) <= kHalfFov)
      seen.push_back({o.pan, o.tilt, o.peak, 1000.0});
  return seen;
}

/// One recorded step: pan and tilt commands [rad], pan rate [rad/s], target [rad] (NaN = none).
struct Sample
{
  double command, tilt_command, rate, target;
};

enum class Scenario
{
  kExplore,     // four objects of different saliency and tilt: selection, habituation, saccades, tilt
  kIdle,        // objects vanish after 8 s: memory fade and the idle timeout
  kTrack,       // a target moving sinusoidally, tracked
  kLookAhead,   // look_ahead with a salient object far to the side
  kModes,       // explore -> hold -> track -> explore (repulsion reset) -> look_ahead
  kBadInput,    // NaN and out-of-range regions, pan, tilt and dt; random frame times
};

std::vector<Sample> run(Scenario scenario)
{
  HeadAttractorParameters p;
  HeadAttractor head(p);
  Lcg rng(12345);
  double pan = 0.0, tilt = p.default_tilt, t = 0.0;
  const std::vector<Object> table = {{deg(-60), deg(20), 0.9}, {deg(-15), deg(30), 0.6}, {deg(15), deg(10), 0.8},
                                     {deg(45), deg(25), 0.7}};
  std::vector<Sample> samples;
  if (scenario == Scenario::kLookAhead)
  {
    head.setBehaviour(HeadAttractor::Behaviour::kLookAhead);
    pan = deg(50);  // the object in view
  }
  for (int k = 0; k < kSteps; ++k)
  {
    double dt = kDt, pan_in = pan, tilt_in = tilt;
    std::vector<SeenRegion> regions;
    switch (scenario)
    {
      case Scenario::kExplore:
        regions = look(table, pan);
        break;
      case Scenario::kIdle:
        if (t < 8.0)
          regions = look(table, pan);
        break;
      case Scenario::kTrack:
      {
        const Object target{deg(55) * std::sin(0.2 * t), deg(15), 0.8};
        head.setBehaviour(HeadAttractor::Behaviour::kTrack, target.pan);
        regions = look({target}, pan);
        break;
      }
      case Scenario::kLookAhead:
        regions = look({{deg(60), deg(20), 0.9}}, pan);
        break;
      case Scenario::kModes:
        if (k == 80)
          head.setBehaviour(HeadAttractor::Behaviour::kHold);
        else if (k == 140)
          head.setBehaviour(HeadAttractor::Behaviour::kTrack, deg(-40));
        else if (k == 220)
          head.setBehaviour(HeadAttractor::Behaviour::kExplore);
        else if (k == 320)
          head.setBehaviour(HeadAttractor::Behaviour::kLookAhead);
        regions = look(table, pan);
        break;
      case Scenario::kBadInput:
      {
        regions = look(table, pan);
        const int extra = static_cast<int>(rng.unit() * 4);
        for (int i = 0; i < extra; ++i)
          regions.push_back({(rng.unit() - 0.5) * 8, (rng.unit() - 0.5) * 4, rng.unit() * 3 - 1, 500.0});
        if (k % 17 == 0)
          regions.push_back({NAN, 0.0, 0.9, 500.0});
        if (k % 19 == 0)
          regions.push_back({deg(5), NAN, NAN, 500.0});
        if (k % 23 == 0)
          regions.push_back({deg(-5), INFINITY, 0.9, 500.0});
        dt = k % 29 == 0 ? NAN : (k % 31 == 0 ? -0.2 : kDt * (0.2 + 2 * rng.unit()));
        if (k % 37 == 0)
          pan_in = NAN;
        if (k % 41 == 0)
          tilt_in = NAN;
        if (k % 43 == 0)
          pan_in = 5.0;  // beyond the limits
        break;
      }
    }
    const HeadAttractor::Output out = head.update(regions, pan_in, t, dt, kHalfFov, tilt_in);
    if (k % kSampleEvery == kSampleEvery - 1)
      samples.push_back({out.command, out.tilt_command, out.rate, out.target});
    pan = servo(pan, out.command);
    tilt = servo(tilt, out.tilt_command);
    t += std::isfinite(dt) && dt > 0 ? dt : kDt;
  }
  return samples;
}

const char* const kScenarioNames[] = {"explore", "idle", "track", "look_ahead", "modes", "bad_input"};

// Recorded from commit f7cfe83 (before the split of update()), printed with %.17g.
const std::vector<std::vector<Sample>> kGolden = {
    // GOLDEN-BEGIN
    {  // explore
        {0.14578998052262562, 0.18980063801043051, 0.068438719596526698, 0.26179938779914941},
        {0.17595019144776133, 0.1763891475757581, 0.059786556160902206, 0.26179938779914941},
        {0.78539816339744828, 0.40637332214827437, 1.622034304371974, 0.78539816339744828},
        {0.66540201297645329, 0.43268981075657559, -0.18398562624738155, 0.78539816339744828},
        {0.78539816339744828, 0.43588946942313872, 0.68699492202323642, 0.78539816339744828},
        {0.21725021637437036, 0.38898637994514579, -1.0980478588767666, 0.26725354171163163},
        {0.22559123793575003, 0.20079317224696802, -0.14925550585808761, 0.26179939300063593},
        {0.23508358909667068, 0.17772568515003798, -0.1357453100311567, 0.26179938779915435},
        {-0.3544681326447931, 0.42475841778164775, 0.2480166268558098, -0.26179938779914941},
        {0.22264921733854232, 0.34879471884152741, -0.39834490143716805, 0.26179938779914946},
        {-0.083031801678675188, 0.37987137803045057, 0.50049737797646021, 0.26179938779914946},
        {0.036411866291685524, 0.26535703701788904, -0.85751392581288599, -0.26179938779914941},
        {0.19238424247202129, 0.37263622064329743, 0.40844713809424094, 0.26179938779914946},
        {0.11922412143741179, 0.23324572370324709, -0.43854555014096785, -0.26179938779914941},
        {-0.017343859662449765, 0.39407270406618922, 0.26812164700215646, 0.26179938779914946},
        {0.87115295892222588, 0.30768692854726526, 0.11369219398954065, 0.78522772108768324},
        {-0.21981067058990109, 0.28435184940260372, -1.4431340356712059, 0.26179938779914946},
        {0.24563176658238939, 0.18789362533819365, 0.2503522217558698, 0.26179938779914946},
        {0.10320436886107182, 0.17615729113151762, 0.26029642045591272, 0.26179938779914946},
        {-0.37259175297872105, 0.3167216556924729, -1.2626888491004482, -0.26179938779914941},
    },
    {  // idle
        {0.14578998052262562, 0.18980063801043051, 0.068438719596526698, 0.26179938779914941},
        {0.17595019144776133, 0.1763891475757581, 0.059786556160902206, 0.26179938779914941},
        {0.78539816339744828, 0.40637332214827437, 1.622034304371974, 0.78539816339744828},
        {0.66540201297645329, 0.43268981075657559, -0.18398562624738155, 0.78539816339744828},
        {-0.12844136349164648, 0.34660100859931625, 0.17329536335744913, NAN},
        {-0.37356379265585854, 0.30566630368178066, -0.040899807453705694, NAN},
        {0, 0.30068889151987044, 2.1626160229392095, 0},
        {-0.0067439453548506119, 0.30008375312865171, 0.016859713622820741, 0},
        {-7.7752641795230998e-05, 0.30001018242519711, 0.00019438160425856022, 0},
        {-8.9642692803344125e-07, 0.30000123794519112, 2.2410673200832515e-06, 0},
        {-1.0335098826384662e-08, 0.30000015050523493, 2.5837747065961657e-08, 0},
        {-1.1915557689175859e-10, 0.30000001829792294, 2.9788894222939648e-10, 0},
        {-1.3737702699234315e-12, 0.30000000222460022, 3.4344256748085786e-12, 0},
        {-1.5838492865842773e-14, 0.30000000027045942, 3.9596232164606928e-14, 0},
        {-1.8260539025592257e-16, 0.30000000003288152, 4.5651347563980639e-16, 0},
        {-2.1052968128317869e-18, 0.30000000000399757, 5.2632420320794672e-18, 0},
        {-2.4272419690940229e-20, 0.30000000000048599, 6.0681049227350576e-20, 0},
        {-2.7984194630527652e-22, 0.30000000000005911, 6.9960486576319148e-22, 0},
        {-3.2263579778638782e-24, 0.30000000000000721, 8.0658949446596951e-24, 0},
        {-3.7197374942391257e-26, 0.30000000000000088, 9.2993437355978148e-26, 0},
    },
    {  // track
        {0.28379888128543401, 0.266444080940965, 0.18046398393071639, 0.35605808998647076},
        {0.61608534114955071, 0.26236407475480394, 0.14743580513479532, 0.67509977846083247},
        {0.85218615548716825, 0.26186804055137014, 0.088408147070736479, 0.88755805601405213},
        {0.9537346631475373, 0.26180773437109511, 0.015389308619403927, 0.95989043215431091},
        {0.90469877563623458, 0.26180040254744386, -0.060047133810841598, 0.88067721513376607},
        {0.7128464848664634, 0.26244453310299487, -0.1259925739305485, 0.66242443017928831},
        {0.408473586832587, 0.26337393701837147, -0.17205103360141252, 0.33958939309169489},
        {0.039612137413416695, 0.26333853373862115, -0.1909605905553691, -0.036859342271542021},
        {-0.33552509823039645, 0.26198665145669825, -0.1797274586595001, -0.40748879795353843},
        {-0.657706591091479, 0.26182215468820658, -0.14010929642028574, -0.71378473230471084},
        {-0.87604055731031949, 0.26180215572135651, -0.078357946419119293, -0.90738975212777906},
        {-0.95604340276421151, 0.26179972431387161, -0.0042361951660927826, -0.95773788178097208},
        {-0.88510103195453349, 0.26447340439364925, 0.070540960676775871, -0.85688025864701634},
        {-0.67443915289836331, 0.26226961926824466, 0.13417210695001278, -0.62074008376076439},
        {-0.35731858294108698, 0.26294863220187559, 0.17662717870544689, -0.28659869848522856},
        {0.016218418505309539, 0.26303121980745342, 0.19121078422287047, 0.092790319547290168},
        {0.38721802156211271, 0.26283392747155632, 0.17560984756438811, 0.45752978639737296},
        {0.69709745866769346, 0.26280991693420225, 0.13227235468326659, 0.75003536014289185},
        {0.89690684377417695, 0.2639590809623778, 0.068040150059221358, 0.92412684230367148},
        {0.95509143743863067, 0.26206422384622924, -0.0069310437640406715, 0.95231901577103817},
    },
    {  // look_ahead
        {0.0084440653108785735, 0.29999999999999999, -0.021109869296543043, 0},
        {0.9950097717319224, 0.29999999999999999, -0.049811993857174108, 1.0471975511965976},
        {0.78615552840555913, 0.29999999999999999, 0.45549920883904732, 1.0471975511965976},
        {0.010016416370089772, 0.29999999999999999, -0.025040550244897892, 0},
        {1.0232628569473592, 0.29999999999999999, -0.0074247861103029084, 1.0471975511965976},
        {0.76733399201237418, 0.29999999999999999, 0.20872695034274405, 1.0471975511965976},
        {0.0091129672190259324, 0.29999999999999999, -0.022782048523754341, 0},
        {1.023162897518697, 0.29999999999999999, -0.0074557991480686423, 1.0471975511965976},
        {0.76339456814544548, 0.29999999999999999, 0.20684800217099925, 1.0471975511965976},
        {0.0090347318510958039, 0.29999999999999999, -0.022586469539509626, 0},
        {0.99511516572326941, 0.29999999999999999, -0.049711399215551941, 1.0471975511965976},
        {0.78967444785590213, 0.29999999999999999, 0.45921751839350755, 1.0471975511965976},
        {0.0071758856458573623, 0.29999999999999999, -0.017939533691515554, 0},
        {1.02153733827485, 0.29999999999999999, -0.016097220113786802, 1.0471975511965976},
        {0.79244678752933395, 0.29999999999999999, 0.29676399622535282, 1.0471975511965976},
        {0.0072178877357357528, 0.29999999999999999, -0.018044535729480254, 0},
        {1.0215435365755714, 0.29999999999999999, -0.016093331643628125, 1.0471975511965976},
        {0.79268670795396112, 0.29999999999999999, 0.29687355678844884, 1.0471975511965976},
        {0.0072215237404607297, 0.29999999999999999, -0.018053625463674856, 0},
        {1.0215440731430034, 0.29999999999999999, -0.016092995030980144, 1.0471975511965976},
    },
    {  // modes
        {0.14578998052262562, 0.18980063801043051, 0.068438719596526698, 0.26179938779914941},
        {0.17595019144776133, 0.1763891475757581, 0.059786556160902206, 0.26179938779914941},
        {0.78539816339744828, 0.40637332214827437, 1.622034304371974, 0.78539816339744828},
        {0.66540201297645329, 0.43268981075657559, -0.18398562624738155, 0.78539816339744828},
        {0.66540201297645329, 0.43268981075657559, 0, NAN},
        {0.66540201297645329, 0.43268981075657559, 0, NAN},
        {0.66540201297645329, 0.43268981075657559, 0, NAN},
        {-0.68753646806799595, 0.31614836181500072, -0.02648750107058314, -0.69813170079773179},
        {-0.69800954512895974, 0.3019632933035879, -0.00030538917104012302, -0.69813170079773179},
        {-0.69813029243875591, 0.30023869068483844, -3.5208974396006202e-06, -0.69813170079773179},
        {-0.69813168456045827, 0.30002901921503977, -4.0593183703307987e-08, -0.69813170079773179},
        {-0.95612021858127338, 0.34310329046373872, 0.1982016758312462, -1.0471975511965976},
        {-1.0180373892396211, 0.3483409408242959, -0.47683884550263311, -1.0471975511965976},
        {-1.1321568317379049, 0.34897771831524066, 0.06860402646150679, -1.0471975511965976},
        {-1.1446163878072368, 0.34905513559497181, 0.6285831215484512, -1.0471975511965976},
        {-0.98081538686770153, 0.34906454772885381, 0.028950436655519815, -1.0471975511965976},
        {-0.4805790115397901, 0.30596593102154468, 0.016485710393210617, -1.0471975511965976},
        {-1.4686087145167575, 0.30072531942249892, 0.21200541071311274, -1.0471975511965976},
        {-0.013096059496603909, 0.30008818191156983, 0.03273905206783468, 0},
        {-0.21890324995364169, 0.3000107208618088, 0.21169753619742337, 0.26316292627727},
    },
    {  // bad_input
        {0.18226827125709161, 0.18447418955816405, 0.24590155118574458, 0.26179938779914941},
        {0.1317766327557483, 0.13373747864572741, 0.49314487059128431, 0.26215827514252199},
        {0.19127127972602737, 0.16989370176185439, -0.072003403809387065, 0.26179394773037956},
        {0.43615634200071085, 0.21433494487809213, 0.63758571366402794, 0.26177278833893081},
        {0.87622652010174373, 0.40949700895264357, -0.10992123658673277, 0.78539816339744828},
        {0.17796361683608813, 0.23411868633259, 0.2826802162950674, 0.26179936182311403},
        {0.014130502682760927, 0.22414242468523338, -0.42421736528858772, -0.043633231299858237},
        {-0.15455102511761909, 0.4756564146631882, 0.17448805840819132, -0.25724587408975386},
        {-0.093307677502707242, 0.49575630697588458, 0.080994262867997102, -0.2617993791140113},
        {-0.42722753238633848, 0.44759208105675191, 0.19728528784988258, -0.26223577271738607},
        {1.2511654720972658, 0.34884852538868527, 1.1428105435036446, 0.77448985557248362},
        {0.77835240637507641, 0.41588107262105328, -0.12393544154066928, 0.78538751075308799},
        {0.78539816335681167, 0.41604424427898024, 0.37819196520947829, 0.78539816335681167},
        {0.8385484585611912, 0.43171848311659583, -0.34980338390701332, 0.78539816339744828},
        {-0.2703582411124606, 0.32186006875279066, -0.60492409032278949, -0.26179938946382575},
        {-0.16846551827438358, 0.51041058319108801, -0.28130326938038042, -0.26179938779915257},
        {-0.26857218914429087, 0.46732575623338829, -0.52204669133045845, -0.26179938779914946},
        {0.3563199145744041, 0.23746563316885858, -0.25373096747993157, 0.27175272255662497},
        {-0.23486345793092336, 0.20668906113671848, 0.2670005523474262, 0.2618042478258864},
        {0.12015734259815146, 0.1779531229693867, 0.037574874750379794, 0.26179938809578185},
    },
    // GOLDEN-END
};

// A C++ literal that reads back as exactly `x`.
std::string literal(double x)
{
  if (std::isnan(x))
    return "NAN";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

void printGolden()
{
  std::printf("    // GOLDEN-BEGIN\n");
  for (int s = 0; s < 6; ++s)
  {
    std::printf("    {  // %s\n", kScenarioNames[s]);
    for (const Sample& x : run(static_cast<Scenario>(s)))
      std::printf("        {%s, %s, %s, %s},\n", literal(x.command).c_str(), literal(x.tilt_command).c_str(),
                  literal(x.rate).c_str(), literal(x.target).c_str());
    std::printf("    },\n");
  }
  std::printf("    // GOLDEN-END\n");
}
}  // namespace

TEST(HeadAttractorGolden, TrajectoriesMatchTheRecordedImplementation)
{
  ASSERT_EQ(kGolden.size(), 6u) << "golden table missing: regenerate it (see the file's header)";
  double worst = 0.0;
  for (int s = 0; s < 6; ++s)
  {
    const std::vector<Sample> now = run(static_cast<Scenario>(s));
    const std::vector<Sample>& golden = kGolden[s];
    ASSERT_EQ(now.size(), golden.size()) << kScenarioNames[s];
    for (size_t i = 0; i < now.size(); ++i)
    {
      const std::string where = std::string(kScenarioNames[s]) + " sample " + std::to_string(i);
      EXPECT_NEAR(now[i].command, golden[i].command, kTolerance) << where;
      EXPECT_NEAR(now[i].tilt_command, golden[i].tilt_command, kTolerance) << where;
      EXPECT_NEAR(now[i].rate, golden[i].rate, kTolerance) << where;
      if (std::isnan(golden[i].target))
        EXPECT_TRUE(std::isnan(now[i].target)) << where;
      else
        EXPECT_NEAR(now[i].target, golden[i].target, kTolerance) << where;
      worst = std::max({worst, std::abs(now[i].command - golden[i].command),
                        std::abs(now[i].tilt_command - golden[i].tilt_command), std::abs(now[i].rate - golden[i].rate)});
    }
  }
  RecordProperty("worst_difference", std::to_string(worst));
  std::printf("largest difference to the recorded trajectories: %.3g\n", worst);
}

// The scenarios must exercise what they claim, or the comparison above proves little.
TEST(HeadAttractorGolden, ScenariosCoverBothSidesLookAheadAndHold)
{
  const std::vector<Sample> explore = run(Scenario::kExplore);
  double lowest = 1e9, highest = -1e9;
  int with_target = 0;
  for (const Sample& x : explore)
  {
    lowest = std::min(lowest, x.command);
    highest = std::max(highest, x.command);
    with_target += std::isfinite(x.target);
  }
  EXPECT_LT(lowest, deg(-10));
  EXPECT_GT(highest, deg(40));
  EXPECT_GT(with_target, 10);
  int ahead = 0, aside = 0;
  for (const Sample& x : run(Scenario::kLookAhead))
  {
    ahead += std::abs(x.command) < deg(5);
    aside += x.command > deg(40);
  }
  EXPECT_GT(ahead, 0);
  EXPECT_GT(aside, 0);
  int no_target = 0;
  for (const Sample& x : run(Scenario::kBadInput))
    ASSERT_TRUE(std::isfinite(x.command) && std::isfinite(x.tilt_command) && std::isfinite(x.rate));
  for (const Sample& x : run(Scenario::kModes))
    no_target += std::isnan(x.target);
  EXPECT_GT(no_target, 0) << "hold should report no target";
}

int main(int argc, char** argv)
{
  if (const char* print = std::getenv("BIOVISION_PRINT_GOLDEN"); print && std::string(print) == "1")
  {
    printGolden();
    return 0;
  }
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

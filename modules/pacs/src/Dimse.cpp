// DIMSE with DCMTK: C-ECHO, C-FIND, C-GET (DcmSCU receiving the C-STOREs itself), C-MOVE (to
// mvw's own storage SCP, a DcmSCP on a thread), C-STORE.
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <set>
#include <thread>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmnet/dcmlayer.h>
#include <dcmtk/dcmnet/dcmtrans.h>
#include <dcmtk/dcmnet/dimse.h>
#include <dcmtk/dcmnet/diutil.h>
#include <dcmtk/dcmnet/scp.h>
#include <dcmtk/dcmnet/scu.h>

#include "Internal.h"
#include "mvw/core/Error.h"

namespace fs = std::filesystem;

namespace mvw::pacs::detail {

namespace {

const OFList<OFString>& uncompressed() {
  static const OFList<OFString> list = [] {
    OFList<OFString> l;
    l.push_back(UID_LittleEndianExplicitTransferSyntax);
    l.push_back(UID_LittleEndianImplicitTransferSyntax);
    l.push_back(UID_BigEndianExplicitTransferSyntax);
    return l;
  }();
  return list;
}

std::string where(const Server& server) { return server.text; }

// A DIMSE message that has started must go on at kLowSpeedBytesPerSecond or more, as a DICOMweb
// answer must (curl's low-speed limit, DicomWeb.cpp). DCMTK bounds each read of a started message
// by the socket time-out only, so a server that trickled a byte every half second held mvw for as
// long as it went on (issue 50's fault suite: the DIMSE trickle). PacedConnection follows the
// PDUs it reads (a 6-byte header that gives the body's length): between two PDUs, waiting is
// the DIMSE time-out's business (a server that thinks, mvw writing what it received); within
// one, a window of the read time-out that brings less than 1 kB a second ends the association.
thread_local double pacedWindowS = 60;  // the read time-out of this thread's association
thread_local bool tooSlow = false;      // set when a PacedConnection stopped a trickle

class PacedConnection : public DcmTCPConnection {
 public:
  PacedConnection(DcmNativeSocketType socket, double windowS)
      : DcmTCPConnection(socket), windowS_(windowS) {}

  ssize_t read(void* buf, size_t nbyte) override {
    if (headerBytes_ > 0 && seconds(Clock::now() - windowStart_) > windowS_) {
      if (double(windowBytes_) < double(kLowSpeedBytesPerSecond) * windowS_) {
        tooSlow = true;
        ::shutdown(getSocket(), SHUT_RDWR);
        errno = ETIMEDOUT;
        return -1;
      }
      windowStart_ = Clock::now();
      windowBytes_ = 0;
    }
    const ssize_t n = DcmTCPConnection::read(buf, nbyte);
    if (n > 0) follow(static_cast<const unsigned char*>(buf), static_cast<std::size_t>(n));
    return n;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  void follow(const unsigned char* p, std::size_t n) {
    windowBytes_ += n;
    while (n > 0) {
      if (headerBytes_ == 0) {  // a PDU starts: its window with it
        windowStart_ = Clock::now();
        windowBytes_ = n;
      }
      if (headerBytes_ < 6) {
        const std::size_t take = std::min<std::size_t>(6 - headerBytes_, n);
        for (std::size_t i = 0; i < take; ++i) header_[headerBytes_++] = p[i];
        p += take;
        n -= take;
        if (headerBytes_ == 6)
          bodyLeft_ = (std::uint32_t(header_[2]) << 24) | (std::uint32_t(header_[3]) << 16) |
                      (std::uint32_t(header_[4]) << 8) | std::uint32_t(header_[5]);
      } else {
        const std::size_t take = std::min<std::size_t>(bodyLeft_, n);
        bodyLeft_ -= take;
        p += take;
        n -= take;
      }
      if (headerBytes_ == 6 && bodyLeft_ == 0) headerBytes_ = 0;  // the PDU is whole
    }
  }

  double windowS_;
  Clock::time_point windowStart_{};
  std::size_t windowBytes_ = 0;
  unsigned char header_[6] = {};
  std::size_t headerBytes_ = 0;  // 0: between PDUs
  std::uint64_t bodyLeft_ = 0;
};

// Hands DCMTK a PacedConnection for each association: a plain TCP one, no TLS.
class PacedLayer : public DcmTransportLayer {
 public:
  DcmTransportConnection* createConnection(DcmNativeSocketType socket, OFBool) override {
    return new PacedConnection(socket, pacedWindowS);
  }
};

// Every association mvw requests goes through a PacedLayer: DcmSCU::useSecureConnection, the
// one door to the connection DCMTK makes, is protected, and it needs the network and the
// association's parameters, which initNetwork makes.
class PacedScu : public DcmSCU {
 public:
  OFCondition pace() {
    static PacedLayer layer;
    return useSecureConnection(&layer);
  }
};

// `callingAet`: the AE title mvw called as, named in the hint when the server aborted (issue
// 51: Orthanc accepts the association of an AE title it does not know, then aborts its C-FIND
// or C-GET, which DCMTK reports as "Peer aborted Association").
[[noreturn]] void fail(const Server& server, const std::string& what, const OFCondition& cond,
                       const std::string& callingAet = {}) {
  // DCMTK's texts can hold several lines: one message, one line.
  std::string text = cond.text();
  for (std::size_t at; (at = text.find('\n')) != std::string::npos;) text.replace(at, 1, "; ");
  if (tooSlow)
    text = "the answer came slower than 1 kB a second for " + std::to_string(int(pacedWindowS)) +
           " s in the middle of a message (--read-timeout): stopped (" + text + ")";
  if (cond == DUL_PEERABORTEDASSOCIATION && !callingAet.empty())
    text += " (check that the server knows the calling AE title '" + callingAet +
            "': a PACS answers only the AE titles it lists, Orthanc under DicomModalities; give "
            "the one it knows with --calling-aet or calling_aet in servers.json)";
  throw ServiceError(where(server) + ": " + what + ": " + text);
}

// The DIMSE time-out bounds the wait for a message to start; the rest of a message that has
// started is read blocking, bounded only by DCMTK's socket time-outs (60 s by default, process
// wide): a server that stops in the middle of an answer waited that long, past --read-timeout
// (issue 50's fault suite, tests/faults). They follow the read time-out.
void setSocketTimeouts(const Options& options) {
  const auto seconds = static_cast<Sint32>(std::max(1.0, std::ceil(options.readTimeoutS)));
  dcmSocketReceiveTimeout.set(seconds);
  dcmSocketSendTimeout.set(seconds);
}

void configure(PacedScu& scu, const Server& server, const Options& options) {
  quietDcmtk();
  scu.setAETitle(options.callingAet.c_str());
  scu.setPeerHostName(server.host.c_str());
  scu.setPeerPort(static_cast<Uint16>(server.port));
  scu.setPeerAETitle(server.calledAet.c_str());
  scu.setConnectionTimeout(static_cast<Sint32>(std::max(1.0, options.connectTimeoutS)));
  scu.setACSETimeout(static_cast<Uint32>(std::max(1.0, options.connectTimeoutS)));
  scu.setDIMSEBlockingMode(DIMSE_NONBLOCKING);
  scu.setDIMSETimeout(static_cast<Uint32>(std::max(1.0, options.readTimeoutS)));
  setSocketTimeouts(options);
  pacedWindowS = std::max(1.0, options.readTimeoutS);
  tooSlow = false;
}

void associate(PacedScu& scu, const Server& server, const Options& options) {
  OFCondition cond = scu.initNetwork();
  if (cond.bad()) fail(server, "cannot start the network", cond);
  cond = scu.pace();
  if (cond.bad()) fail(server, "cannot start the network", cond);
  cond = scu.negotiateAssociation();
  if (cond == DUL_ASSOCIATIONREJECTED)
    throw ServiceError(where(server) + ": refused the association (check the called AE title '" +
                       server.calledAet + "' and that the server knows the calling AE title '" +
                       options.callingAet + "')");
  if (cond.bad()) fail(server, "no association", cond);
}

// A C-STORE of a retrieve, with the instance in memory: written to the staging folder under a
// temporary name and handed to the receiver. Errors are kept for after the retrieve (they must
// not unwind through DCMTK).
struct StoreSink {
  Receiver* receiver = nullptr;
  std::exception_ptr error;
  std::mutex mutex;
  int counter = 0;

  Uint16 accept(DcmDataset* dataset) {
    std::lock_guard lock(mutex);
    if (error) return STATUS_STORE_Refused_OutOfResources;
    try {
      E_TransferSyntax xfer = dataset->getOriginalXfer();
      if (xfer == EXS_Unknown) xfer = EXS_LittleEndianExplicit;
      DcmFileFormat file(dataset);
      const fs::path tmp = receiver->staging() / (".store-" + std::to_string(++counter));
      OFCondition cond = file.saveFile(tmp.c_str(), xfer);
      if (cond.bad()) throw Error("cannot write " + tmp.string() + ": " + cond.text());
      receiver->acceptFile(tmp);
      return STATUS_Success;
    } catch (...) {
      error = std::current_exception();
      return STATUS_STORE_Refused_OutOfResources;
    }
  }
};

class GetScu : public PacedScu {
 public:
  StoreSink sink;

 protected:
  OFCondition handleSTORERequest(const T_ASC_PresentationContextID, DcmDataset* incoming,
                                 OFBool& continueSession, Uint16& status) override {
    status = incoming ? sink.accept(incoming) : STATUS_STORE_Error_CannotUnderstand;
    delete incoming;
    continueSession = status == STATUS_Success;
    return EC_Normal;
  }
};

class MoveScp : public DcmSCP {
 public:
  StoreSink sink;
  std::atomic<bool> stop{false};

 protected:
  OFCondition handleIncomingCommand(T_DIMSE_Message* message,
                                    const DcmPresentationContextInfo& info) override {
    if (message->CommandField != DIMSE_C_STORE_RQ)
      return DcmSCP::handleIncomingCommand(message, info);
    T_DIMSE_C_StoreRQ& request = message->msg.CStoreRQ;
    DcmDataset* dataset = nullptr;
    OFCondition cond = receiveSTORERequest(request, info.presentationContextID, dataset);
    if (cond.bad()) {
      delete dataset;
      return cond;
    }
    const Uint16 status = dataset ? sink.accept(dataset) : STATUS_STORE_Error_CannotUnderstand;
    delete dataset;
    return sendSTOREResponse(info.presentationContextID, request, status);
  }
  OFBool stopAfterConnectionTimeout() override { return stop.load(); }
  OFBool stopAfterCurrentAssociation() override { return stop.load(); }
};

std::string statusText(Uint16 status) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "%04x", status);
  return std::string("status 0x") + hex;
}

void checkRetrieve(const Server& server, const char* what, OFCondition cond,
                   OFList<RetrieveResponse*>& responses, StoreSink& sink, const Options& options) {
  Uint16 status = 0, failed = 0;
  bool any = false;
  for (RetrieveResponse* r : responses) {
    status = r->m_status;
    failed = r->m_numberOfFailedSubops;
    any = true;
    delete r;
  }
  responses.clear();
  if (sink.error) std::rethrow_exception(sink.error);
  if (cond.bad()) fail(server, std::string(what) + " broke off", cond, options.callingAet);
  if (!any) throw ServiceError(where(server) + ": " + what + " ended without a response");
  if (status == STATUS_MOVE_Failed_MoveDestinationUnknown)
    throw ServiceError(where(server) + ": " + what +
                       " refused: the server does not know the destination AE title (a PACS "
                       "must list mvw's AE title, address and port for C-MOVE)");
  if (status != STATUS_Success || failed > 0)
    throw ServiceError(where(server) + ": " + what + " failed (" + statusText(status) + ", " +
                       std::to_string(failed) + " sub-operations failed)");
}

// The retrieve requests: the series, or (resuming) the missing instances as lists of SOP
// Instance UIDs (list matching on the unique key), at most 1000 to a request.
std::vector<DcmDataset> retrieveKeys(const std::string& studyUid, const std::string& seriesUid,
                                     const std::vector<std::string>& instances) {
  std::vector<DcmDataset> requests;
  std::size_t next = 0;
  do {
    DcmDataset keys;
    keys.putAndInsertString(DCM_QueryRetrieveLevel, instances.empty() ? "SERIES" : "IMAGE");
    keys.putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
    keys.putAndInsertString(DCM_SeriesInstanceUID, seriesUid.c_str());
    if (!instances.empty()) {
      std::string list;
      for (std::size_t n = 0; n < 1000 && next < instances.size(); ++n, ++next)
        list += (list.empty() ? "" : "\\") + instances[next];
      keys.putAndInsertString(DCM_SOPInstanceUID, list.c_str());
    }
    requests.push_back(keys);
  } while (next < instances.size());
  return requests;
}

}  // namespace

double dimseEcho(const Server& server, const Options& options) {
  PacedScu scu;
  configure(scu, server, options);
  scu.addPresentationContext(UID_VerificationSOPClass, uncompressed());
  const auto start = std::chrono::steady_clock::now();
  associate(scu, server, options);
  OFCondition cond = scu.sendECHORequest(0);
  if (cond.bad()) fail(server, "C-ECHO", cond, options.callingAet);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  scu.releaseAssociation();
  return s;
}

Match matchFromIdentifier(DcmDataset& identifier) {
  Match m;
  for (unsigned long i = 0; i < identifier.card(); ++i) {
    DcmElement* e = identifier.getElement(i);
    if (!e || e->ident() == EVR_SQ) continue;
    OFString text;
    e->getOFStringArray(text);
    const std::string keyword = keywordOf(e->getGTag(), e->getETag());
    if (!keyword.empty() && keyword != "QueryRetrieveLevel") m[keyword] = text.c_str();
  }
  return m;
}

std::vector<Match> dimseFind(const Server& server, const std::string& level, const Match& keys,
                             const Options& options) {
  PacedScu scu;
  configure(scu, server, options);
  scu.addPresentationContext(UID_FINDStudyRootQueryRetrieveInformationModel, uncompressed());
  associate(scu, server, options);
  DcmDataset query;
  query.putAndInsertString(DCM_QueryRetrieveLevel, level.c_str());
  for (const auto& [keyword, value] : keys) {
    DcmTag tag;
    if (DcmTag::findTagFromName(keyword.c_str(), tag).bad())
      throw Error("no DICOM keyword " + keyword);
    query.putAndInsertString(tag, value.c_str());
  }
  const T_ASC_PresentationContextID id =
      scu.findPresentationContextID(UID_FINDStudyRootQueryRetrieveInformationModel, "");
  if (id == 0) throw ServiceError(where(server) + ": accepts no Study Root C-FIND");
  OFList<QRResponse*> responses;
  OFCondition cond = scu.sendFINDRequest(id, &query, &responses);
  std::vector<Match> matches;
  Uint16 status = 0;
  for (QRResponse* r : responses) {
    status = r->m_status;
    if (r->m_dataset && DICOM_PENDING_STATUS(r->m_status)) {
      matches.push_back(matchFromIdentifier(*r->m_dataset));
    }
    delete r;
  }
  if (cond.bad()) fail(server, "C-FIND", cond, options.callingAet);
  if (status != STATUS_Success)
    throw ServiceError(where(server) + ": C-FIND failed (" + statusText(status) + ")");
  scu.releaseAssociation();
  return matches;
}

void dimseRetrieve(const Server& server, const std::string& studyUid, const std::string& seriesUid,
                   const std::vector<std::string>& instances, Receiver& receiver,
                   const Options& options) {
  std::vector<DcmDataset> requests = retrieveKeys(studyUid, seriesUid, instances);
  OFList<RetrieveResponse*> responses;
  if (options.moveToAet.empty()) {
    GetScu scu;
    scu.sink.receiver = &receiver;
    configure(scu, server, options);
    scu.addPresentationContext(UID_GETStudyRootQueryRetrieveInformationModel, uncompressed());
    // Every storage class a study may hold, as the SCP role: a C-GET receives over the
    // presentation contexts it proposed (docs/design.md#dicom-networking-traps-already-found).
    for (int i = 0; i < numberOfDcmLongSCUStorageSOPClassUIDs; ++i)
      scu.addPresentationContext(dcmLongSCUStorageSOPClassUIDs[i], uncompressed(), ASC_SC_ROLE_SCP);
    associate(scu, server, options);
    const T_ASC_PresentationContextID id =
        scu.findPresentationContextID(UID_GETStudyRootQueryRetrieveInformationModel, "");
    if (id == 0)
      throw ServiceError(where(server) +
                         ": accepts no Study Root C-GET (many PACS offer only "
                         "C-MOVE: give --move-to AET --port P)");
    for (DcmDataset& keys : requests) {
      OFCondition cond = scu.sendCGETRequest(id, &keys, &responses);
      checkRetrieve(server, "C-GET", cond, responses, scu.sink, options);
    }
    scu.releaseAssociation();
    return;
  }
  // C-MOVE: mvw's storage SCP listens first, then the move is asked for.
  quietDcmtk();
  MoveScp scp;
  scp.sink.receiver = &receiver;
  scp.setPort(static_cast<Uint16>(options.movePort));
  scp.setAETitle(options.moveToAet.c_str());
  scp.setConnectionBlockingMode(DUL_NOBLOCK);
  scp.setConnectionTimeout(1);
  scp.setDIMSETimeout(static_cast<Uint32>(std::max(1.0, options.readTimeoutS)));
  setSocketTimeouts(options);
  scp.setDIMSEBlockingMode(DIMSE_NONBLOCKING);
  scp.addPresentationContext(UID_VerificationSOPClass, uncompressed());
  for (int i = 0; i < numberOfDcmAllStorageSOPClassUIDs; ++i)
    scp.addPresentationContext(dcmAllStorageSOPClassUIDs[i], uncompressed());
  OFCondition cond = scp.openListenPort();
  if (cond.bad())
    throw InputError("--port " + std::to_string(options.movePort),
                     std::string("cannot listen for the C-MOVE: ") + cond.text());
  std::thread listener([&scp] { scp.acceptAssociations(); });
  struct Join {
    MoveScp& scp;
    std::thread& t;
    ~Join() {
      scp.stop = true;
      if (t.joinable()) t.join();
    }
  } join{scp, listener};
  PacedScu scu;
  configure(scu, server, options);
  scu.addPresentationContext(UID_MOVEStudyRootQueryRetrieveInformationModel, uncompressed());
  associate(scu, server, options);
  const T_ASC_PresentationContextID id =
      scu.findPresentationContextID(UID_MOVEStudyRootQueryRetrieveInformationModel, "");
  if (id == 0) throw ServiceError(where(server) + ": accepts no Study Root C-MOVE");
  for (DcmDataset& keys : requests) {
    cond = scu.sendMOVERequest(id, options.moveToAet.c_str(), &keys, &responses);
    // The move's last response comes after its last C-STORE was answered.
    checkRetrieve(server, "C-MOVE", cond, responses, scp.sink, options);
  }
  scu.releaseAssociation();
}

void dimseStore(const Server& server, const std::vector<fs::path>& files, const Options& options) {
  // One presentation context per SOP class and transfer syntax the files hold.
  std::vector<std::pair<std::string, std::string>> classes;
  std::vector<std::pair<std::string, std::string>> perFile;
  for (const fs::path& f : files) {
    DcmFileFormat ff;
    if (ff.loadFileUntilTag(f.c_str(), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect,
                            DCM_PixelData)
            .bad())
      throw InputError(f, "is not a DICOM file");
    OFString sopClass, xfer;
    ff.getMetaInfo()->findAndGetOFString(DCM_MediaStorageSOPClassUID, sopClass);
    ff.getMetaInfo()->findAndGetOFString(DCM_TransferSyntaxUID, xfer);
    if (sopClass.empty()) ff.getDataset()->findAndGetOFString(DCM_SOPClassUID, sopClass);
    if (sopClass.empty()) throw InputError(f, "carries no SOP Class UID");
    if (xfer.empty()) xfer = UID_LittleEndianImplicitTransferSyntax;
    perFile.emplace_back(sopClass.c_str(), xfer.c_str());
    if (std::find(classes.begin(), classes.end(), perFile.back()) == classes.end())
      classes.push_back(perFile.back());
  }
  if (classes.size() > 120)
    throw InputError(files.front(), "the files hold more than 120 kinds of object to store");
  PacedScu scu;
  configure(scu, server, options);
  for (const auto& [sopClass, xfer] : classes) {
    OFList<OFString> syntaxes;
    syntaxes.push_back(xfer.c_str());
    scu.addPresentationContext(sopClass.c_str(), syntaxes);
  }
  associate(scu, server, options);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const T_ASC_PresentationContextID id =
        scu.findPresentationContextID(perFile[i].first.c_str(), perFile[i].second.c_str());
    if (id == 0)
      throw ServiceError(where(server) + ": does not accept " + files[i].string() + " (SOP class " +
                         perFile[i].first + ", transfer syntax " + perFile[i].second + ")");
    Uint16 status = 0;
    OFCondition cond = scu.sendSTORERequest(id, files[i].c_str(), nullptr, status);
    if (cond.bad()) fail(server, "C-STORE of " + files[i].string(), cond);
    if (status != STATUS_Success)
      throw ServiceError(where(server) + ": refused " + files[i].string() + " (C-STORE " +
                         statusText(status) + ")");
  }
  scu.releaseAssociation();
}

}  // namespace mvw::pacs::detail
